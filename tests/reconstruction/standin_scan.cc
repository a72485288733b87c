#include "reconstruction/standin_scan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/core/units.h"
#include "simtree/reconstruction/detail/local_geometry.h"

namespace simtree::test {
namespace {

struct Camera {
  Eigen::Vector3d centre;
  Eigen::Matrix3d world_from_camera;  // columns: right, down, forward
  double focal;

  Eigen::Vector3d ToCamera(const Eigen::Vector3d& p) const {
    return world_from_camera.transpose() * (p - centre);
  }
};

Camera LookAt(const Eigen::Vector3d& centre, const Eigen::Vector3d& target, double focal) {
  const Eigen::Vector3d forward = (target - centre).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Camera camera;
  camera.centre = centre;
  camera.world_from_camera.col(0) = right;
  camera.world_from_camera.col(1) = down;
  camera.world_from_camera.col(2) = forward;
  camera.focal = focal;
  return camera;
}

// The surface nearest to the camera in every pixel.
class DepthBuffer {
 public:
  DepthBuffer(double u0, double v0, int width, int height)
      : u0_(u0),
        v0_(v0),
        width_(width),
        height_(height),
        depth_(static_cast<size_t>(width) * height, std::numeric_limits<double>::infinity()),
        point_(static_cast<size_t>(width) * height) {}

  void Offer(double u, double v, double depth, const Eigen::Vector3d& p) {
    const int x = static_cast<int>(std::floor(u - u0_)), y = static_cast<int>(std::floor(v - v0_));
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    const size_t i = static_cast<size_t>(y) * width_ + x;
    if (depth < depth_[i]) {
      depth_[i] = depth;
      point_[i] = p;
    }
  }
  template <typename F>
  void ForEach(F&& f) const {
    for (size_t i = 0; i < depth_.size(); ++i) {
      if (std::isfinite(depth_[i])) f(point_[i], depth_[i]);
    }
  }

 private:
  double u0_, v0_;
  int width_, height_;
  std::vector<double> depth_;
  std::vector<Eigen::Vector3d> point_;
};

double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = std::clamp((p - a).dot(d) / std::max(d.squaredNorm(), 1e-18), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

}  // namespace

StandInScan ScanLikeAKinect(const Tree& tree, const StandInScanOptions& options) {
  StandInScan scan;
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const Eigen::Vector3d base = tree.trunk().base().position;
  const double height = hi.z() - base.z();
  const Eigen::Vector3d target = base + Eigen::Vector3d(0, 0, 0.5 * height);

  // Points along the wood, for placing occluders and gaps (length-weighted by node spacing).
  std::vector<Eigen::Vector3d> wood;
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) wood.push_back(n.position);
  }
  std::uniform_int_distribution<size_t> pick_wood(0, wood.size() - 1);

  double spacing_sum = 0.0;
  for (int view = 0; view < options.views; ++view) {
    const double angle = kTwoPi * (view + 0.3 * uniform(rng)) / options.views;
    const Eigen::Vector3d centre =
        base + Eigen::Vector3d(options.camera_distance_m * std::cos(angle),
                               options.camera_distance_m * std::sin(angle),
                               options.camera_height_share * height * (0.8 + 0.4 * uniform(rng)));
    const Camera camera = LookAt(centre, target, options.focal_px);
    scan.cameras.push_back(centre);
    // Image bounds from the tree's bounding box.
    double u_lo = 1e18, u_hi = -1e18, v_lo = 1e18, v_hi = -1e18;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                              (corner & 4) ? hi.z() : lo.z());
      const Eigen::Vector3d q = camera.ToCamera(p);
      const double z = std::max(q.z(), 0.3);
      u_lo = std::min(u_lo, camera.focal * q.x() / z);
      u_hi = std::max(u_hi, camera.focal * q.x() / z);
      v_lo = std::min(v_lo, camera.focal * q.y() / z);
      v_hi = std::max(v_hi, camera.focal * q.y() / z);
    }
    DepthBuffer buffer(u_lo - 2, v_lo - 2, static_cast<int>(u_hi - u_lo) + 4,
                       static_cast<int>(v_hi - v_lo) + 4);
    for (const Branch& b : tree.branches) {
      for (size_t k = 0; k + 1 < b.nodes.size(); ++k) {
        const Node& n0 = b.nodes[k];
        const Node& n1 = b.nodes[k + 1];
        const Eigen::Vector3d axis = n1.position - n0.position;
        const double length = axis.norm();
        if (length < 1e-9) continue;
        const Eigen::Vector3d a = axis / length;
        const double depth = camera.ToCamera(0.5 * (n0.position + n1.position)).z();
        if (depth <= 0.1) continue;
        const double pixel = depth / camera.focal;
        const double r_mid = 0.5 * (n0.radius + n1.radius);
        if (2.0 * r_mid / pixel < options.min_diameter_px) continue;  // too thin to see
        const double step = 0.5 * pixel;
        Eigen::Vector3d e1, e2;
        reconstruction::PlaneBasis(a, &e1, &e2);
        const int along = std::max(1, static_cast<int>(std::ceil(length / step)));
        const int around = std::max(
            6, static_cast<int>(std::ceil(kTwoPi * std::max(n0.radius, n1.radius) / step)));
        for (int i = 0; i < along; ++i) {
          const double s = (i + 0.5) / along;
          const double r = n0.radius + s * (n1.radius - n0.radius);
          const Eigen::Vector3d on_axis = n0.position + s * axis;
          for (int j = 0; j < around; ++j) {
            const double theta = kTwoPi * (j + 0.5 * (i & 1)) / around;
            const Eigen::Vector3d normal = std::cos(theta) * e1 + std::sin(theta) * e2;
            const Eigen::Vector3d q = on_axis + r * normal;
            if (normal.dot(centre - q) <= 0.0) continue;  // faces away
            const Eigen::Vector3d c = camera.ToCamera(q);
            if (c.z() <= 0.1) continue;
            buffer.Offer(camera.focal * c.x() / c.z(), camera.focal * c.y() / c.z(), c.z(), q);
          }
        }
      }
    }
    // Leafy occluders between the camera and the tree.
    std::vector<Eigen::Vector3d> occluders;
    for (int o = 0; o < options.occluders_per_view; ++o) {
      const Eigen::Vector3d w = wood[pick_wood(rng)];
      occluders.push_back(centre + (0.4 + 0.4 * uniform(rng)) * (w - centre));
    }
    double depth_sum = 0.0;
    size_t seen = 0;
    buffer.ForEach([&](const Eigen::Vector3d& q, double depth) {
      for (const Eigen::Vector3d& o : occluders) {
        if (SegmentDistance(o, centre, q) < options.occluder_radius_m) return;
      }
      const double sigma = options.noise_at_2m_m * (depth / 2.0) * (depth / 2.0);
      const Eigen::Vector3d ray = (q - centre).normalized();
      const Eigen::Vector3d across1 = ray.cross(Eigen::Vector3d::UnitZ()).normalized();
      const Eigen::Vector3d across2 = ray.cross(across1);
      const double lateral = options.lateral_noise_share * sigma;
      scan.points.push_back(q + sigma * gauss(rng) * ray + lateral * gauss(rng) * across1 +
                            lateral * gauss(rng) * across2);
      depth_sum += depth;
      ++seen;
    });
    if (seen > 0) spacing_sum += depth_sum / seen / camera.focal;
  }
  scan.mean_spacing_m = options.views > 0 ? spacing_sum / options.views : 0.0;

  // Gaps hidden from every view.
  for (int g = 0; g < options.hidden_gaps; ++g) {
    const Eigen::Vector3d centre = wood[pick_wood(rng)];
    std::erase_if(scan.points, [&](const Eigen::Vector3d& p) {
      return (p - centre).norm() < options.hidden_gap_radius_m;
    });
  }
  // Stray outliers in the tree's box.
  const size_t outliers = static_cast<size_t>(options.outlier_share * scan.points.size());
  for (size_t i = 0; i < outliers; ++i) {
    scan.points.push_back(
        lo + (hi - lo).cwiseProduct(Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng))));
  }
  return scan;
}

Tree MakeStandInTree(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  auto between = [&](double a, double b) { return a + (b - a) * uniform(rng); };
  Tree tree;
  tree.metadata.species = "stand-in";
  tree.metadata.source = "MakeStandInTree seed " + std::to_string(seed);
  const double node_step = 0.05;
  const double tip_radius = 0.003;

  // Adds a branch from `start` along `direction` (bending slowly towards the light) and returns
  // its id.
  auto add_branch = [&](int parent, int parent_node, const Eigen::Vector3d& start,
                        Eigen::Vector3d direction, double length, double base_radius) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    const int count = std::max(2, static_cast<int>(std::ceil(length / node_step)) + 1);
    Eigen::Vector3d p = start;
    for (int i = 0; i < count; ++i) {
      const double s = static_cast<double>(i) / (count - 1);
      b.nodes.push_back({p, base_radius + s * (tip_radius - base_radius)});
      // Trunks wander less than branches; branches bend up towards the light.
      const double wander = parent < 0 ? 0.03 : 0.08;
      direction = (direction + Eigen::Vector3d(between(-wander, wander), between(-wander, wander),
                                               parent < 0 ? 0.0 : 0.04))
                      .normalized();
      p += direction * length / (count - 1);
    }
    tree.branches.push_back(std::move(b));
    return tree.size() - 1;
  };
  auto child_direction = [&](const Eigen::Vector3d& axis, double azimuth, double elevation) {
    Eigen::Vector3d e1, e2;
    reconstruction::PlaneBasis(axis, &e1, &e2);
    return (std::cos(elevation) * axis +
            std::sin(elevation) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2))
        .normalized();
  };

  const double height = between(2.5, 3.5);
  add_branch(-1, 0, Eigen::Vector3d::Zero(),
             Eigen::Vector3d(between(-0.1, 0.1), between(-0.1, 0.1), 1.0).normalized(), height,
             between(0.06, 0.12));
  // Children on a golden-angle spiral, level by level.
  std::vector<int> parents = {0};
  for (int level = 1; level <= 3; ++level) {
    std::vector<int> next;
    for (const int parent_id : parents) {
      const int count = level == 1   ? static_cast<int>(between(5, 9))
                        : level == 2 ? static_cast<int>(between(2, 5))
                                     : static_cast<int>(between(0, 4));
      const double parent_length = tree.branches[parent_id].Length();
      double azimuth = between(0, kTwoPi);
      for (int c = 0; c < count; ++c) {
        const Branch& parent = tree.branches[parent_id];
        const double at = (level == 1 ? between(0.3, 0.9) : between(0.25, 0.85));
        const int node = std::clamp(static_cast<int>(at * (parent.nodes.size() - 1)), 1,
                                    static_cast<int>(parent.nodes.size()) - 2);
        const Eigen::Vector3d axis =
            (parent.nodes[node + 1].position - parent.nodes[node - 1].position).normalized();
        azimuth += 2.39996;  // golden angle
        const double elevation = DegToRad(between(35, 65));
        const double length = parent_length * (1.0 - 0.6 * at) * between(0.35, 0.6);
        const double radius = parent.nodes[node].radius * between(0.4, 0.65);
        if (length < 0.1 || radius < 0.004) continue;
        const Eigen::Vector3d start = parent.nodes[node].position;
        next.push_back(add_branch(parent_id, node, start, child_direction(axis, azimuth, elevation),
                                  length, radius));
      }
    }
    parents = std::move(next);
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

}  // namespace simtree::test
