#include "simtree/report/detail/cloud_thumbnail.h"

#include <algorithm>
#include <cmath>

namespace simtree::report {

RgbImage CloudThumbnail(const std::vector<Eigen::Vector3d>& camera_points, int width, int height) {
  RgbImage image(width, height, 255);
  if (camera_points.empty() || width < 8 || height < 8) return image;
  Eigen::Vector3d lo = camera_points.front(), hi = lo;
  for (const Eigen::Vector3d& p : camera_points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double margin = 4;
  const double scale = std::min((width - 2 * margin) / std::max(hi.x() - lo.x(), 1e-6),
                                (height - 2 * margin) / std::max(hi.y() - lo.y(), 1e-6));
  const double x0 = (width - scale * (hi.x() - lo.x())) / 2;
  const double y0 = (height - scale * (hi.y() - lo.y())) / 2;
  const double depth = std::max(hi.z() - lo.z(), 1e-6);
  // Far points first, so near ones are drawn over them.
  std::vector<const Eigen::Vector3d*> order;
  order.reserve(camera_points.size());
  for (const Eigen::Vector3d& p : camera_points) order.push_back(&p);
  std::sort(order.begin(), order.end(), [](auto* a, auto* b) { return a->z() > b->z(); });
  for (const Eigen::Vector3d* p : order) {
    const int x = static_cast<int>(std::lround(x0 + scale * (p->x() - lo.x())));
    const int y = static_cast<int>(std::lround(y0 + scale * (p->y() - lo.y())));
    if (x < 0 || y < 0 || x >= width || y >= height) continue;
    const double t = (p->z() - lo.z()) / depth;  // 0 near, 1 far
    image.at(x, y, 0) = static_cast<uint8_t>(30 + 170 * t);
    image.at(x, y, 1) = static_cast<uint8_t>(90 + 130 * t);
    image.at(x, y, 2) = static_cast<uint8_t>(40 + 160 * t);
  }
  return image;
}

}  // namespace simtree::report
