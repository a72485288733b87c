#include "simtree/registration/detail/cloud_picture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

// Robust bounds (2nd to 98th percentile per axis) of a panel's points in (across, depth, up).
struct Bounds {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Ones();
};

Eigen::Vector3d ToView(const Eigen::Vector3d& p, const Eigen::Vector3d& across,
                       const Eigen::Vector3d& depth) {
  return {p.dot(across), p.dot(depth), p.z()};
}

Bounds PanelBounds(const PicturePanel& panel, const Eigen::Vector3d& across,
                   const Eigen::Vector3d& depth) {
  std::array<std::vector<double>, 3> values;
  for (const PictureLayer& layer : panel.layers) {
    if (!layer.points) continue;
    const size_t step = std::max<size_t>(1, layer.points->size() / 20000);
    for (size_t i = 0; i < layer.points->size(); i += step) {
      const Eigen::Vector3d v = ToView((*layer.points)[i], across, depth);
      for (int a = 0; a < 3; ++a) values[a].push_back(v[a]);
    }
  }
  Bounds b;
  if (values[0].empty()) return b;
  for (int a = 0; a < 3; ++a) {
    auto& v = values[a];
    std::sort(v.begin(), v.end());
    b.lo[a] = v[v.size() * 2 / 100];
    b.hi[a] = v[std::min(v.size() - 1, v.size() * 98 / 100)];
  }
  return b;
}

}  // namespace

std::array<uint8_t, 3> ViewColor(int index) {
  static constexpr std::array<std::array<uint8_t, 3>, 12> kPalette = {{{228, 26, 28},
                                                                       {55, 126, 184},
                                                                       {77, 175, 74},
                                                                       {152, 78, 163},
                                                                       {255, 127, 0},
                                                                       {166, 86, 40},
                                                                       {247, 129, 191},
                                                                       {0, 170, 170},
                                                                       {120, 120, 120},
                                                                       {200, 180, 0},
                                                                       {0, 0, 120},
                                                                       {120, 0, 0}}};
  return kPalette[static_cast<size_t>(std::abs(index)) % kPalette.size()];
}

void PictureOptions::Validate() const {
  CheckAtLeast("panel_width", panel_width, 64);
  CheckAtLeast("side_height", side_height, 64);
  CheckAtLeast("top_height", top_height, 64);
  if (!(side_direction.head<2>().norm() > 0)) {
    throw OptionError("side_direction", "expected a horizontal direction (x or y not 0)");
  }
}

RgbImage DrawPanels(const std::vector<PicturePanel>& panels, const PictureOptions& options) {
  options.Validate();
  if (panels.empty()) throw InputError("<memory>", "picture", "expected at least one panel");
  const Eigen::Vector3d depth =
      Eigen::Vector3d(options.side_direction.x(), options.side_direction.y(), 0).normalized();
  const Eigen::Vector3d across = depth.cross(Eigen::Vector3d::UnitZ()) * -1.0;
  const int title_h = 34;
  const int w = options.panel_width;
  const int legend_h = options.legend.empty() ? 0 : 30;
  const int height = title_h + options.side_height + options.top_height + legend_h;
  cv::Mat canvas(height, w * static_cast<int>(panels.size()), CV_8UC3, cv::Scalar(255, 255, 255));
  const Bounds common = PanelBounds(panels.back(), across, depth);

  for (size_t k = 0; k < panels.size(); ++k) {
    const PicturePanel& panel = panels[k];
    const Bounds b = options.common_scale ? common : PanelBounds(panel, across, depth);
    const Eigen::Vector3d centre = 0.5 * (b.lo + b.hi);
    const double extent_side = std::max(
        {(b.hi - b.lo).x() / (w - 40.0), (b.hi - b.lo).z() / (options.side_height - 40.0), 1e-6});
    const double extent_top = std::max(
        {(b.hi - b.lo).x() / (w - 40.0), (b.hi - b.lo).y() / (options.top_height - 40.0), 1e-6});
    const int x0 = static_cast<int>(k) * w;
    // Depth buffers: nearer points (smaller depth coordinate in the side view, higher z from
    // above) are drawn over farther ones.
    std::vector<double> side_z(static_cast<size_t>(w) * options.side_height,
                               std::numeric_limits<double>::infinity());
    std::vector<double> top_z(static_cast<size_t>(w) * options.top_height,
                              -std::numeric_limits<double>::infinity());
    for (const PictureLayer& layer : panel.layers) {
      if (!layer.points) continue;
      const cv::Vec3b colour(layer.color[2], layer.color[1], layer.color[0]);
      for (const Eigen::Vector3d& p : *layer.points) {
        const Eigen::Vector3d v = ToView(p, across, depth) - centre;
        const int su = static_cast<int>(std::lround(w / 2.0 + v.x() / extent_side));
        const int sv =
            static_cast<int>(std::lround(options.side_height / 2.0 - v.z() / extent_side));
        const int tu = static_cast<int>(std::lround(w / 2.0 + v.x() / extent_top));
        const int tv = static_cast<int>(std::lround(options.top_height / 2.0 - v.y() / extent_top));
        for (int dy = 0; dy < layer.dot_px; ++dy) {
          for (int dx = 0; dx < layer.dot_px; ++dx) {
            const int u1 = su + dx, v1 = sv + dy;
            if (u1 >= 0 && u1 < w && v1 >= 0 && v1 < options.side_height &&
                v.y() < side_z[v1 * w + u1]) {
              side_z[v1 * w + u1] = v.y();
              canvas.at<cv::Vec3b>(title_h + v1, x0 + u1) = colour;
            }
            const int u2 = tu + dx, v2 = tv + dy;
            if (u2 >= 0 && u2 < w && v2 >= 0 && v2 < options.top_height &&
                v.z() > top_z[v2 * w + u2]) {
              top_z[v2 * w + u2] = v.z();
              canvas.at<cv::Vec3b>(title_h + options.side_height + v2, x0 + u2) = colour;
            }
          }
        }
      }
    }
    cv::putText(canvas, panel.title, cv::Point(x0 + 10, 24), cv::FONT_HERSHEY_SIMPLEX, 0.6,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    cv::putText(canvas, "side", cv::Point(x0 + 10, title_h + 18), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
    cv::putText(canvas, "top", cv::Point(x0 + 10, title_h + options.side_height + 18),
                cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
    cv::line(canvas, cv::Point(x0, title_h + options.side_height),
             cv::Point(x0 + w, title_h + options.side_height), cv::Scalar(200, 200, 200));
    if (k > 0) {
      cv::line(canvas, cv::Point(x0, 0), cv::Point(x0, height - legend_h),
               cv::Scalar(160, 160, 160));
    }
  }
  int legend_x = 10;
  for (const auto& [text, color] : options.legend) {
    const int y = height - legend_h / 2;
    cv::rectangle(canvas, cv::Point(legend_x, y - 6), cv::Point(legend_x + 12, y + 6),
                  cv::Scalar(color[2], color[1], color[0]), cv::FILLED);
    cv::putText(canvas, text, cv::Point(legend_x + 16, y + 5), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    legend_x += 24 + 8 * static_cast<int>(text.size());
  }
  RgbImage image(canvas.cols, canvas.rows);
  for (int y = 0; y < canvas.rows; ++y) {
    for (int x = 0; x < canvas.cols; ++x) {
      const cv::Vec3b c = canvas.at<cv::Vec3b>(y, x);
      image.at(x, y, 0) = c[2];
      image.at(x, y, 1) = c[1];
      image.at(x, y, 2) = c[0];
    }
  }
  return image;
}

}  // namespace simtree::registration
