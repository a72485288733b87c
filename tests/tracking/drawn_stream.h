#pragma once
// A pull stream drawn for tests: red tape bands (axis-aligned rectangles, anti-aliased by their
// pixel coverage) over a textured brown-green background, with depth, at known 3D centres.

#include <cmath>
#include <filesystem>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"

namespace simtree::test {

struct DrawnStream {
  CameraIntrinsics intrinsics{.width = 320,
                              .height = 288,
                              .fx = 217.0,
                              .fy = 217.0,
                              .cx = 159.5,
                              .cy = 143.5,
                              .depth_scale_m = 0.001};
  double fps = 30.0;
  double half_length_m = 0.02;  // band half-extent along the (vertical) branch
  double radius_m = 0.012;      // branch radius: the band's half-width
  uint8_t tape[3] = {200, 25, 30};
  // positions[frame][marker]: the band centre on the branch axis, camera frame (m).
  std::vector<std::vector<Eigen::Vector3d>> positions;
};

// Coverage of pixel (x, y) (its square [x - 0.5, x + 0.5]) by the rectangle [x0, x1] x [y0, y1].
inline double Coverage(int x, int y, double x0, double x1, double y0, double y1) {
  const double w = std::max(0.0, std::min(x + 0.5, x1) - std::max(x - 0.5, x0));
  const double h = std::max(0.0, std::min(y + 0.5, y1) - std::max(y - 0.5, y0));
  return w * h;
}

// The true box [x, y, w, h] of a band.
inline std::array<double, 4> DrawnBox(const DrawnStream& s, const Eigen::Vector3d& p) {
  const Eigen::Vector2d c = s.intrinsics.Project(p);
  const double hw = s.radius_m * s.intrinsics.fx / p.z();
  const double hh = s.half_length_m * s.intrinsics.fy / p.z();
  return {c.x() - hw, c.y() - hh, 2 * hw, 2 * hh};
}

inline RgbdImage DrawFrame(const DrawnStream& s, const std::vector<Eigen::Vector3d>& markers) {
  const CameraIntrinsics& k = s.intrinsics;
  RgbdImage image{RgbImage(k.width, k.height), DepthImage(k.width, k.height, 4000), k};
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const int n = (x * 7 + y * 13) % 23;  // a deterministic texture
      image.color.at(x, y, 0) = static_cast<uint8_t>(90 + n);
      image.color.at(x, y, 1) = static_cast<uint8_t>(85 + n);
      image.color.at(x, y, 2) = static_cast<uint8_t>(60 + n);
    }
  }
  // Far markers first, so a nearer band covers a farther one.
  std::vector<size_t> order(markers.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return markers[a].z() > markers[b].z(); });
  for (size_t i : order) {
    const Eigen::Vector3d& p = markers[i];
    if (p.z() <= 0.0) continue;
    const auto box = DrawnBox(s, p);
    const double surface_mm = 1000.0 * (p.z() - 0.85 * s.radius_m);
    for (int y = std::max(0, int(box[1]) - 1);
         y <= std::min(k.height - 1, int(box[1] + box[3]) + 1); ++y) {
      for (int x = std::max(0, int(box[0]) - 1);
           x <= std::min(k.width - 1, int(box[0] + box[2]) + 1); ++x) {
        const double c = Coverage(x, y, box[0], box[0] + box[2], box[1], box[1] + box[3]);
        if (c <= 0.0) continue;
        for (int ch = 0; ch < 3; ++ch) {
          image.color.at(x, y, ch) = static_cast<uint8_t>(
              std::lround(c * s.tape[ch] + (1 - c) * image.color.at(x, y, ch)));
        }
        if (c >= 0.5) image.depth.at(x, y) = static_cast<uint16_t>(std::lround(surface_mm));
      }
    }
  }
  return image;
}

// Writes the stream as a pull/ folder (intrinsics.json, frames.csv, markers.json, frames) and
// returns the init at frame 0 (the projected centres).
inline TrackInit WriteDrawnStream(const DrawnStream& s, const std::filesystem::path& pull) {
  std::filesystem::create_directories(pull);
  WriteIntrinsicsJson(s.intrinsics, pull / "intrinsics.json");
  std::vector<PullFrame> rows;
  for (size_t f = 0; f < s.positions.size(); ++f) {
    const RgbdImage image = DrawFrame(s, s.positions[f]);
    rows.push_back(WritePullFrame(pull, static_cast<int>(f), f / s.fps, image.color, image.depth));
  }
  WriteFramesCsv(rows, pull / "frames.csv");
  std::vector<MarkerLink> links;
  for (size_t m = 0; m < s.positions[0].size(); ++m) {
    links.push_back(MarkerLink{.id = static_cast<int>(m),
                               .label = fmt::format("m{}", m),
                               .parent = m == 0 ? -1 : 0,
                               .branch = std::nullopt});
  }
  WriteMarkersJson(links, pull / "markers.json");
  TrackInit init;
  for (size_t m = 0; m < s.positions[0].size(); ++m) {
    init.markers.push_back({static_cast<int>(m), s.intrinsics.Project(s.positions[0][m])});
  }
  return init;
}

}  // namespace simtree::test
