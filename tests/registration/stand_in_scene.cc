#include "stand_in_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <fmt/format.h>

#include "simtree/core/tree_file.h"
#include "simtree/core/tree_json.h"
#include "simtree/io/point_cloud_io.h"

namespace fs = std::filesystem;

namespace simtree::test {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Distance along the unit ray (origin o, direction d) to a capsule (segment a-b, radius r), or -1.
double RayCapsule(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, double r) {
  const Eigen::Vector3d ba = b - a;
  const Eigen::Vector3d oa = o - a;
  const double baba = ba.dot(ba), bard = ba.dot(d), baoa = ba.dot(oa);
  const double rdoa = d.dot(oa), oaoa = oa.dot(oa);
  const double qa = baba - bard * bard;
  const double qb = baba * rdoa - baoa * bard;
  const double qc = baba * oaoa - baoa * baoa - r * r * baba;
  double h = qb * qb - qa * qc;
  if (h >= 0.0 && qa > 1e-12) {
    const double t = (-qb - std::sqrt(h)) / qa;
    const double y = baoa + t * bard;
    if (y > 0.0 && y < baba) return t;
    // The end spheres.
    const Eigen::Vector3d oc = y <= 0.0 ? oa : Eigen::Vector3d(o - b);
    const double sb = d.dot(oc);
    const double sc = oc.dot(oc) - r * r;
    h = sb * sb - sc;
    if (h > 0.0) return -sb - std::sqrt(h);
  }
  return -1.0;
}

Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target, double roll) {
  const Eigen::Vector3d forward = (target - eye).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d rotation;
  rotation.col(0) = right;
  rotation.col(1) = down;
  rotation.col(2) = forward;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = eye;
  return pose;
}

double TreeHeight(const Tree& tree) {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  return hi.z();
}

}  // namespace

CameraIntrinsics StandInIntrinsics() {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 576;
  k.fx = k.fy = 504.0;
  k.cx = 319.5;
  k.cy = 287.5;
  return k;
}

Tree LoadDemoTree(const fs::path& path, double height_m, double radius_scale) {
  Tree tree = ReadTreeFile(path);
  const Eigen::Vector3d base = tree.trunk().base().position;
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const double scale = height_m / (hi.z() - base.z());
  for (Branch& branch : tree.branches) {
    for (Node& node : branch.nodes) {
      node.position = scale * (node.position - base);
      node.radius *= scale * radius_scale;
    }
  }
  for (Marker& marker : tree.markers) marker.position = scale * (marker.position - base);
  return tree;
}

std::vector<ViewPose> StandInPoses(double tree_height_m, const StandInOptions& options) {
  std::mt19937_64 rng(options.seed * 7919 + 17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double first = options.first_angle_deg >= 0 ? options.first_angle_deg * kDeg
                                                    : unit(rng) * 2 * std::numbers::pi;
  std::vector<ViewPose> poses;
  for (int v = 0; v < options.views; ++v) {
    const double angle = first + v * options.angle_step_deg * kDeg;
    const double distance =
        options.min_distance_m + unit(rng) * (options.max_distance_m - options.min_distance_m);
    const Eigen::Vector3d eye(distance * std::cos(angle), distance * std::sin(angle),
                              options.camera_height_m + options.height_jitter_m * gauss(rng));
    Eigen::Vector3d target(0, 0, options.aim_height_fraction * tree_height_m);
    // Aim jitter: move the target sideways and up by the jitter angle at the target's distance.
    const double reach = (target - eye).norm();
    const Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(target - eye).normalized();
    target += side * reach * std::tan(options.aim_jitter_deg * kDeg * gauss(rng));
    target.z() += reach * std::tan(options.aim_jitter_deg * kDeg * gauss(rng));
    ViewPose pose;
    pose.name = fmt::format("view_{:02d}", v);
    pose.world_from_camera = LookAt(eye, target, options.roll_jitter_deg * kDeg * gauss(rng));
    poses.push_back(pose);
  }
  return poses;
}

RgbdImage RenderStandInView(const Tree& tree, const Eigen::Isometry3d& world_from_camera,
                            const StandInOptions& options, uint64_t view_seed) {
  std::mt19937_64 rng(view_seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const CameraIntrinsics k = StandInIntrinsics();
  const int w = k.width, h = k.height;
  const Eigen::Isometry3d camera_from_world = world_from_camera.inverse();
  const Eigen::Vector3d eye = world_from_camera.translation();
  constexpr double kNone = std::numeric_limits<double>::infinity();
  std::vector<double> depth(static_cast<size_t>(w) * h, kNone);
  std::vector<int> label(static_cast<size_t>(w) * h, -1);  // branch id, -2 ground

  auto ray = [&](int u, int v) {  // unit ray in the camera frame
    return Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0).normalized();
  };

  // Ground plane z = 0.
  if (options.ground) {
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        const Eigen::Vector3d d_cam = ray(u, v);
        const Eigen::Vector3d d = world_from_camera.linear() * d_cam;
        if (d.z() >= -1e-6) continue;
        const double t = -eye.z() / d.z();
        depth[v * w + u] = t * d_cam.z();
        label[v * w + u] = -2;
      }
    }
  }

  // Branch segments as capsules, each over its projected bounding box.
  for (const Branch& branch : tree.branches) {
    const Eigen::Vector3d sway =
        options.sway_m * branch.level * Eigen::Vector3d(gauss(rng), gauss(rng), 0.3 * gauss(rng));
    for (size_t n = 0; n + 1 < branch.nodes.size(); ++n) {
      const Eigen::Vector3d a =
          camera_from_world * (branch.nodes[n].position + (n ? sway : Eigen::Vector3d::Zero()));
      const Eigen::Vector3d b = camera_from_world * (branch.nodes[n + 1].position + sway);
      const double r = 0.5 * (branch.nodes[n].radius + branch.nodes[n + 1].radius);
      if (a.z() < options.min_range_m || b.z() < options.min_range_m) continue;
      // Narrow surfaces vanish, softly around the threshold.
      const double width_px = 2.0 * r * k.fx / (0.5 * (a.z() + b.z()));
      if (width_px < options.min_pixel_width * (1.0 + 0.15 * gauss(rng))) continue;
      const Eigen::Vector2d pa = k.Project(a), pb = k.Project(b);
      const double pad = r * k.fx / std::min(a.z(), b.z()) + 1.0;
      const int u0 = std::max(0, static_cast<int>(std::floor(std::min(pa.x(), pb.x()) - pad)));
      const int u1 = std::min(w - 1, static_cast<int>(std::ceil(std::max(pa.x(), pb.x()) + pad)));
      const int v0 = std::max(0, static_cast<int>(std::floor(std::min(pa.y(), pb.y()) - pad)));
      const int v1 = std::min(h - 1, static_cast<int>(std::ceil(std::max(pa.y(), pb.y()) + pad)));
      for (int v = v0; v <= v1; ++v) {
        for (int u = u0; u <= u1; ++u) {
          const Eigen::Vector3d d = ray(u, v);
          const double t = RayCapsule(Eigen::Vector3d::Zero(), d, a, b, r);
          if (t <= 0) continue;
          const double z = t * d.z();
          if (z < depth[v * w + u]) {
            depth[v * w + u] = z;
            label[v * w + u] = branch.id;
          }
        }
      }
    }
  }

  // Flying pixels at silhouettes: an in-between depth.
  std::vector<double> measured = depth;
  for (int v = 1; v + 1 < h; ++v) {
    for (int u = 1; u + 1 < w; ++u) {
      const double z = depth[v * w + u];
      const double neighbours[4] = {depth[v * w + u - 1], depth[v * w + u + 1],
                                    depth[(v - 1) * w + u], depth[(v + 1) * w + u]};
      double far = z;
      for (double n : neighbours) {
        if (n > far) far = n;
      }
      if (std::isfinite(z) && far - z > 0.1 && unit(rng) < options.flying_pixel_rate) {
        const double end = std::isfinite(far) ? far : z + 1.0;
        measured[v * w + u] = z + unit(rng) * (end - z);
      }
    }
  }

  RgbdImage image;
  image.intrinsics = k;
  image.depth = DepthImage(w, h, 0);
  image.color = RgbImage(w, h, 0);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const size_t i = static_cast<size_t>(v) * w + u;
      double z = measured[i];
      if (unit(rng) < options.outlier_rate) {
        z = options.min_range_m + unit(rng) * (options.max_range_m - options.min_range_m);
      }
      const int l = label[i];
      uint8_t rgb[3] = {150, 190, 235};  // sky
      if (l == -2) {
        rgb[0] = 90, rgb[1] = 110, rgb[2] = 60;
      } else if (l >= 0) {
        rgb[0] = 105, rgb[1] = 90, rgb[2] = 80;
      }
      const double shade = 1.0 + 0.08 * gauss(rng);
      for (int c = 0; c < 3; ++c) {
        image.color.at(u, v, c) = static_cast<uint8_t>(std::clamp(rgb[c] * shade, 0.0, 255.0));
      }
      if (!std::isfinite(z)) continue;
      z += (options.noise_a_m + options.noise_b_per_m * z * z) * gauss(rng);
      if (z < options.min_range_m || z > options.max_range_m) continue;
      image.depth.at(u, v) = static_cast<uint16_t>(std::lround(z * 1000.0));
    }
  }
  return image;
}

std::vector<ViewPose> WriteStandInCapture(const Tree& tree, const StandInOptions& options,
                                          const fs::path& root) {
  fs::remove_all(root);
  fs::create_directories(root / "gt");
  CaptureInfo info;
  info.sensor = "stand-in (tests/registration/stand_in_scene.h), not synth";
  info.species = tree.metadata.species;
  info.notes = fmt::format("seed {}", options.seed);
  WriteCaptureInfo(info, root / "capture.json");
  const std::vector<ViewPose> poses = StandInPoses(TreeHeight(tree), options);
  for (size_t v = 0; v < poses.size(); ++v) {
    const RgbdImage image =
        RenderStandInView(tree, poses[v].world_from_camera, options, options.seed * 1000 + v);
    WriteScanView(root, poses[v].name, image);
  }
  WriteScanPoses(poses, root / "gt" / "scan_poses.json");
  WriteTreeJson(tree, root / "gt" / "tree.json");
  return poses;
}

open3d::geometry::PointCloud LoadRealScan(const fs::path& path) {
  open3d::geometry::PointCloud scan = ReadPointCloud(path);
  double z_min = std::numeric_limits<double>::infinity();
  for (const auto& p : scan.points_) z_min = std::min(z_min, p.z());
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto& p : scan.points_) {
    if (p.z() < z_min + 0.3) {
      base += p;
      ++count;
    }
  }
  base /= std::max(count, 1);
  base.z() = z_min;
  for (auto& p : scan.points_) p -= base;
  return scan;
}

open3d::geometry::PointCloud CutStandInView(const open3d::geometry::PointCloud& scan,
                                            const Eigen::Isometry3d& world_from_camera,
                                            const StandInOptions& options, uint64_t view_seed) {
  std::mt19937_64 rng(view_seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const CameraIntrinsics k = StandInIntrinsics();
  const Eigen::Isometry3d camera_from_world = world_from_camera.inverse();
  open3d::geometry::PointCloud in_view;
  for (const auto& p : scan.points_) {
    const Eigen::Vector3d c = camera_from_world * p;
    if (c.z() < options.min_range_m || c.z() > options.max_range_m) continue;
    if (!k.Contains(k.Project(c).x(), k.Project(c).y())) continue;
    in_view.points_.push_back(c);
  }
  open3d::geometry::PointCloud view;
  if (in_view.points_.size() >= 4) {
    const double diameter = (in_view.GetMaxBound() - in_view.GetMinBound()).norm();
    auto [mesh, visible] = in_view.HiddenPointRemoval(Eigen::Vector3d::Zero(), diameter * 100.0);
    for (size_t i : visible) {
      const Eigen::Vector3d& c = in_view.points_[i];
      const double z = c.z();
      const double sigma = options.noise_a_m + options.noise_b_per_m * z * z;
      view.points_.push_back(c * (1.0 + sigma * gauss(rng) / z));
    }
  }
  // Ground seen through every other pixel, and outliers.
  const Eigen::Vector3d eye = world_from_camera.translation();
  for (int v = 0; v < k.height; v += 2) {
    for (int u = 0; u < k.width; u += 2) {
      const Eigen::Vector3d d_cam((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
      if (unit(rng) < options.outlier_rate * 4) {
        view.points_.push_back(d_cam * (options.min_range_m +
                                        unit(rng) * (options.max_range_m - options.min_range_m)));
        continue;
      }
      if (!options.ground) continue;
      const Eigen::Vector3d d = world_from_camera.linear() * d_cam;
      if (d.z() >= -1e-6) continue;
      double z = -eye.z() / d.z();
      if (z < options.min_range_m || z > options.max_range_m) continue;
      z += (options.noise_a_m + options.noise_b_per_m * z * z) * gauss(rng);
      view.points_.push_back(d_cam * z);
    }
  }
  return view;
}

}  // namespace simtree::test
