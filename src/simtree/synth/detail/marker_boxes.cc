#include "simtree/synth/detail/marker_boxes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

constexpr int kRimSamples = 32;
constexpr double kNearZ = 1e-3;  // metres: points nearer the camera plane cannot be projected

struct PixelBox {
  double x0 = std::numeric_limits<double>::infinity();
  double y0 = std::numeric_limits<double>::infinity();
  double x1 = -std::numeric_limits<double>::infinity();
  double y1 = -std::numeric_limits<double>::infinity();
  bool behind = false;  // part of the band is behind the camera plane
  bool any = false;
  void Add(double x, double y) {
    x0 = std::min(x0, x);
    y0 = std::min(y0, y);
    x1 = std::max(x1, x);
    y1 = std::max(y1, y);
    any = true;
  }
};

// Adds the projection of a circle (centre, axis normal, radius; world frame) to `box`.
void AddRim(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius,
            const Eigen::Isometry3d& camera_from_world, const CameraIntrinsics& k, PixelBox& box) {
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Vector3d e1 = a.unitOrthogonal();
  const Eigen::Vector3d e2 = a.cross(e1);
  // The sampled polygon lies inside the circle; grow it to circumscribe the circle.
  const double r = radius / std::cos(std::numbers::pi / kRimSamples);
  for (int i = 0; i < kRimSamples; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / kRimSamples;
    const Eigen::Vector3d p =
        camera_from_world * (center + r * (std::cos(angle) * e1 + std::sin(angle) * e2));
    if (p.z() <= kNearZ) {
      box.behind = true;
      continue;
    }
    box.Add(k.fx * p.x() / p.z() + k.cx, k.fy * p.y() / p.z() + k.cy);
  }
}

// The projected box of a band, unclipped.
PixelBox ProjectBand(const SensorScene& scene, const MarkerBand& band,
                     const Eigen::Isometry3d& camera_from_world, const CameraIntrinsics& k) {
  const Tree& tree = scene.tree();
  const TreePose& pose = scene.pose();
  const Branch& branch = tree.branches[band.branch];
  const std::vector<double> arcs = branch.ArcLengths();
  const double begin = std::clamp(band.begin, 0.0, arcs.back());
  const double end = std::clamp(band.end, 0.0, arcs.back());
  // Tape slightly proud of the curve's surface and the cone's radius between nodes: 2%.
  constexpr double kRadiusMargin = 1.02;
  constexpr double kAbsoluteMargin = 1e-4;
  PixelBox box;
  for (double s : {begin, end}) {
    AddRim(pose.PointAt(tree, band.branch, s), pose.TangentAt(tree, band.branch, s),
           scene.RadiusAt(band.branch, s) * kRadiusMargin + kAbsoluteMargin, camera_from_world, k,
           box);
  }
  // Joints inside the band: the rims of both segments, grown by the bend (the joint's sphere
  // bulges past the two rims by r (1 / cos(bend / 2) - 1)).
  for (size_t i = 1; i + 1 < arcs.size(); ++i) {
    if (arcs[i] <= begin || arcs[i] >= end) continue;
    const Eigen::Vector3d before = pose.node(band.branch, i) - pose.node(band.branch, i - 1);
    const Eigen::Vector3d after = pose.node(band.branch, i + 1) - pose.node(band.branch, i);
    if (before.norm() <= 0 || after.norm() <= 0) continue;
    const double cos_bend = std::clamp(before.normalized().dot(after.normalized()), -1.0, 1.0);
    const double half_bend_cos = std::sqrt(0.5 * (1.0 + cos_bend));
    const double radius =
        branch.nodes[i].radius * kRadiusMargin / std::max(half_bend_cos, 0.1) + kAbsoluteMargin;
    for (const Eigen::Vector3d& axis : {before, after}) {
      AddRim(pose.node(band.branch, i), axis, radius, camera_from_world, k, box);
    }
  }
  return box;
}

}  // namespace

std::vector<MarkerObservation> ComputeMarkerBoxes(const SensorScene& scene,
                                                  const CameraIntrinsics& k,
                                                  const Eigen::Isometry3d& world_from_camera,
                                                  const LabelImage& labels,
                                                  const MarkerBoxOptions& options) {
  ValidateIntrinsics(k, "intrinsics");
  if (labels.width != k.width || labels.height != k.height ||
      labels.pixels.size() != static_cast<size_t>(k.width) * k.height) {
    throw InputError("<memory>", "label image",
                     "expected the intrinsics' size " + std::to_string(k.width) + "x" +
                         std::to_string(k.height) + ", got " + std::to_string(labels.width) + "x" +
                         std::to_string(labels.height));
  }
  const Tree& tree = scene.tree();
  const Eigen::Isometry3d camera_from_world = world_from_camera.inverse();
  std::vector<MarkerObservation> out(tree.markers.size());
  for (size_t m = 0; m < tree.markers.size(); ++m) {
    const Marker& marker = tree.markers[m];
    out[m].box.id = marker.id;
    if (marker.branch >= 0 && marker.branch < tree.size()) {
      out[m].center_camera =
          camera_from_world * scene.pose().PointAt(tree, marker.branch, marker.arc_length);
    }
  }
  const std::vector<MarkerBand>& bands = scene.marker_bands();
  tbb::parallel_for(size_t{0}, bands.size(), [&](size_t b) {
    const MarkerBand& band = bands[b];
    MarkerObservation& obs = out[band.marker_index];
    PixelBox box = ProjectBand(scene, band, camera_from_world, k);
    if (!box.any) return;  // wholly behind the camera
    if (box.behind) {      // crosses the camera plane: its projection is unbounded
      box.x0 = box.y0 = -0.5;
      box.x1 = k.width - 0.5;
      box.y1 = k.height - 0.5;
    }
    const double x0 = std::max(box.x0, -0.5);
    const double y0 = std::max(box.y0, -0.5);
    const double x1 = std::min(box.x1, k.width - 0.5);
    const double y1 = std::min(box.y1, k.height - 0.5);
    if (x1 <= x0 || y1 <= y0) return;  // outside the image
    obs.box.box = {x0, y0, x1 - x0, y1 - y0};
    // Pixel centres inside the box.
    const int px0 = static_cast<int>(std::ceil(x0));
    const int py0 = static_cast<int>(std::ceil(y0));
    const int px1 = std::min(k.width - 1, static_cast<int>(std::floor(x1)));
    const int py1 = std::min(k.height - 1, static_cast<int>(std::floor(y1)));
    const Eigen::Vector3d origin = world_from_camera.translation();
    for (int y = py0; y <= py1; ++y) {
      for (int x = px0; x <= px1; ++x) {
        if (labels.at(x, y).marker == band.id) ++obs.box.visible_pixels;
        const Eigen::Vector3d direction =
            world_from_camera.linear() * Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1.0);
        if (scene.IntersectMarkerBand(band.marker_index, origin, direction).hit()) {
          ++obs.band_pixels;
        }
      }
    }
    obs.box.visible_fraction =
        obs.band_pixels > 0
            ? std::min(1.0, static_cast<double>(obs.box.visible_pixels) / obs.band_pixels)
            : 0.0;
    obs.box.visible = obs.box.visible_fraction >= options.min_visible_fraction &&
                      obs.box.visible_pixels >= options.min_visible_pixels;
  });
  return out;
}

}  // namespace simtree::synth
