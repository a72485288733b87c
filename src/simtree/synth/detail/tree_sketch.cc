#include "simtree/synth/detail/tree_sketch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "simtree/io/mesh_io.h"

namespace simtree::synth {
namespace {

// One orthographic panel: world -> (u right, v down) pixels inside the panel, and a depth that
// grows away from the viewer.
struct Panel {
  int x0 = 0, width = 0, height = 0;
  Eigen::Matrix3d axes;  // rows: u, v, depth directions
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  double scale = 1.0;  // pixels per metre
  std::vector<float> depth;

  Eigen::Vector3d Project(const Eigen::Vector3d& p) const {
    Eigen::Vector3d q = axes * p + offset;
    return {q.x() * scale, q.y() * scale, q.z()};
  }
};

void Plot(RgbImage& image, const Panel& panel, int u, int v, const Eigen::Vector3i& rgb) {
  if (u < 0 || v < 0 || u >= panel.width || v >= panel.height) return;
  for (int c = 0; c < 3; ++c) image.at(panel.x0 + u, v, c) = static_cast<uint8_t>(rgb[c]);
}

// A tapered capsule from a to b (projected), radii in pixels, shaded as a lit cylinder.
void DrawSegment(RgbImage& image, Panel& panel, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                 double ra, double rb, const Eigen::Vector3i& colour, double depth_lo,
                 double depth_hi) {
  const double r_max = std::max(ra, rb);
  const int u0 = static_cast<int>(std::floor(std::min(a.x(), b.x()) - r_max));
  const int u1 = static_cast<int>(std::ceil(std::max(a.x(), b.x()) + r_max));
  const int v0 = static_cast<int>(std::floor(std::min(a.y(), b.y()) - r_max));
  const int v1 = static_cast<int>(std::ceil(std::max(a.y(), b.y()) + r_max));
  const Eigen::Vector2d pa(a.x(), a.y()), ab(b.x() - a.x(), b.y() - a.y());
  const double length2 = ab.squaredNorm();
  for (int v = std::max(0, v0); v <= std::min(panel.height - 1, v1); ++v) {
    for (int u = std::max(0, u0); u <= std::min(panel.width - 1, u1); ++u) {
      const Eigen::Vector2d p(u + 0.5, v + 0.5);
      const double t = length2 > 0 ? std::clamp((p - pa).dot(ab) / length2, 0.0, 1.0) : 0.0;
      const double r = ra + t * (rb - ra);
      const double d = (p - pa - t * ab).norm();
      if (d > r) continue;
      const double depth = a.z() + t * (b.z() - a.z());
      float& z = panel.depth[static_cast<size_t>(v) * panel.width + u];
      if (depth >= z) continue;
      z = static_cast<float>(depth);
      // Shade across the axis (the line, not the capsule end), so joints show no rings.
      const double line =
          length2 > 0
              ? std::abs(ab.x() * (p.y() - pa.y()) - ab.y() * (p.x() - pa.x())) / std::sqrt(length2)
              : d;
      const double across = std::min(1.0, line / std::max(r, 1e-9));
      const double light = 0.55 + 0.45 * std::sqrt(std::max(0.0, 1.0 - across * across));
      const double fog = depth_hi > depth_lo ? (depth - depth_lo) / (depth_hi - depth_lo) : 0.0;
      const double shade = light * (1.0 - 0.35 * std::clamp(fog, 0.0, 1.0));
      Plot(image, panel, u, v, (colour.cast<double>() * shade).cast<int>());
    }
  }
}

}  // namespace

RgbImage SketchTree(const Tree& tree, const TreeSketchOptions& options) {
  if (tree.empty()) return RgbImage(1, 1, 255);
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  lo.z() = std::min(lo.z(), 0.0);
  const double m = options.margin_m;
  const Eigen::Vector3d extent = (hi - lo).array() + 2 * m;
  const double scale = options.view_height_px / extent.z();
  const int gap = 12;

  std::vector<Panel> panels(3);
  // Front: looking along +Y (x right, z up).
  panels[0].axes << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  panels[0].offset = {-lo.x() + m, hi.z() + m, 0};
  panels[0].width = static_cast<int>(std::ceil(extent.x() * scale));
  panels[0].height = options.view_height_px;
  // Side: looking along -X (y right, z up).
  panels[1].axes << 0, 1, 0, 0, 0, -1, -1, 0, 0;
  panels[1].offset = {-lo.y() + m, hi.z() + m, 0};
  panels[1].width = static_cast<int>(std::ceil(extent.y() * scale));
  panels[1].height = options.view_height_px;
  // Top: looking down (x right, y up).
  panels[2].axes << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  panels[2].offset = {-lo.x() + m, hi.y() + m, 0};
  panels[2].width = static_cast<int>(std::ceil(extent.x() * scale));
  panels[2].height = static_cast<int>(std::ceil(extent.y() * scale));

  int width = 0, height = 0;
  for (Panel& p : panels) {
    p.x0 = width;
    p.scale = scale;
    p.depth.assign(static_cast<size_t>(p.width) * p.height, std::numeric_limits<float>::max());
    width += p.width + gap;
    height = std::max(height, p.height);
  }
  RgbImage image(width - gap, height, 255);
  for (const Panel& p : panels) {
    for (int v = 0; v < p.height; ++v) {
      for (int u = 0; u < p.width; ++u) Plot(image, p, u, v, {236, 241, 246});
    }
  }

  for (Panel& panel : panels) {
    // Depth range for the fog: the tree's extent along the view direction.
    const Eigen::Vector3d d = panel.axes.row(2).transpose();
    const double depth_lo = std::min(d.dot(lo), d.dot(hi)) - 0.1 * extent.norm();
    const double depth_hi = std::max(d.dot(lo), d.dot(hi));
    if (panel.axes(1, 2) != 0.0) {  // ground line in the elevations
      const int v = static_cast<int>(std::lround(panel.Project(Eigen::Vector3d::Zero()).y()));
      for (int u = 0; u < panel.width; ++u) {
        for (int dv = 0; dv < 2; ++dv) Plot(image, panel, u, v + dv, {150, 140, 120});
      }
    }
    for (const Branch& b : tree.branches) {
      const Eigen::Vector3i colour =
          options.colour_by_level ? LevelColour(b.level) : Eigen::Vector3i(105, 95, 85);
      for (size_t i = 1; i < b.nodes.size(); ++i) {
        const double ra = std::max(options.min_width_px / 2, b.nodes[i - 1].radius * scale);
        const double rb = std::max(options.min_width_px / 2, b.nodes[i].radius * scale);
        DrawSegment(image, panel, panel.Project(b.nodes[i - 1].position),
                    panel.Project(b.nodes[i].position), ra, rb, colour, depth_lo, depth_hi);
      }
    }
    if (options.draw_markers) {
      for (const Marker& marker : tree.markers) {
        const Eigen::Vector3d p = panel.Project(marker.position);
        for (int dv = -3; dv <= 3; ++dv) {
          for (int du = -3; du <= 3; ++du) {
            if (du * du + dv * dv <= 10) {
              Plot(image, panel, static_cast<int>(p.x()) + du, static_cast<int>(p.y()) + dv,
                   {220, 20, 20});
            }
          }
        }
      }
    }
    // 1 m scale bar, bottom left.
    const int bar = static_cast<int>(std::lround(scale));
    for (int u = 8; u < 8 + bar; ++u) {
      for (int dv = 0; dv < 3; ++dv) Plot(image, panel, u, panel.height - 10 + dv, {0, 0, 0});
    }
  }
  return image;
}

}  // namespace simtree::synth
