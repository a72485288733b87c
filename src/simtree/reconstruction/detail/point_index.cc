#include "simtree/reconstruction/detail/point_index.h"

#include <open3d/geometry/KDTreeFlann.h>

namespace simtree::reconstruction {

PointIndex::PointIndex(std::span<const Eigen::Vector3d> points)
    : data_(3, points.size()),
      tree_(std::make_unique<open3d::geometry::KDTreeFlann>()),
      size_(static_cast<int>(points.size())) {
  if (points.empty()) return;
  for (size_t i = 0; i < points.size(); ++i) data_.col(i) = points[i];
  tree_->SetMatrixData(data_);
}

PointIndex::~PointIndex() = default;

void PointIndex::Nearest(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
                         std::vector<double>& squared_distances) const {
  indices.clear();
  squared_distances.clear();
  if (size_ == 0 || k <= 0) return;
  tree_->SearchKNN(query, k, indices, squared_distances);
}

void PointIndex::WithinRadius(const Eigen::Vector3d& query, double radius,
                              std::vector<int>& indices,
                              std::vector<double>& squared_distances) const {
  indices.clear();
  squared_distances.clear();
  if (size_ == 0 || !(radius > 0.0)) return;
  tree_->SearchRadius(query, radius, indices, squared_distances);
}

void PointIndex::NearestWithin(const Eigen::Vector3d& query, double radius, int k,
                               std::vector<int>& indices,
                               std::vector<double>& squared_distances) const {
  indices.clear();
  squared_distances.clear();
  if (size_ == 0 || !(radius > 0.0) || k <= 0) return;
  tree_->SearchHybrid(query, radius, k, indices, squared_distances);
}

}  // namespace simtree::reconstruction
