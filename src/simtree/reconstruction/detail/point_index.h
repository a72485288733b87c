#pragma once
// A KD-tree over a fixed set of points (Open3D's nanoflann index) with the three queries
// reconstruction needs. Queries are const and safe to run from several threads at once.
//
// Open3D 0.16's KDTreeFlann searches the matrix it was given, not its own copy (isl-org/Open3D
// #6235, fixed upstream in #6734): the index keeps that matrix alive beside the tree.

#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace open3d::geometry {
class KDTreeFlann;
}

namespace simtree::reconstruction {

class PointIndex {
 public:
  explicit PointIndex(std::span<const Eigen::Vector3d> points);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  int size() const { return size_; }
  // The `k` nearest points (fewer when the set is smaller), nearest first; squared distances.
  void Nearest(const Eigen::Vector3d& query, int k, std::vector<int>& indices,
               std::vector<double>& squared_distances) const;
  // Every point within `radius`, nearest first.
  void WithinRadius(const Eigen::Vector3d& query, double radius, std::vector<int>& indices,
                    std::vector<double>& squared_distances) const;
  // At most `k` points within `radius`, nearest first.
  void NearestWithin(const Eigen::Vector3d& query, double radius, int k, std::vector<int>& indices,
                     std::vector<double>& squared_distances) const;

 private:
  Eigen::MatrixXd data_;  // 3 x n; searched by tree_, so it lives as long as the tree
  std::unique_ptr<open3d::geometry::KDTreeFlann> tree_;
  int size_ = 0;
};

}  // namespace simtree::reconstruction
