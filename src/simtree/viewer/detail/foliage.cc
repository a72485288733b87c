#include "simtree/viewer/detail/foliage.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::viewer {
namespace {

// The leaf frame (x along the leaf, z its upper side's normal) for a leaf pointing along `axis`:
// z as close to world up as the axis allows.
Eigen::Quaternionf LeafFrame(const Eigen::Vector3d& axis, double roll) {
  const Eigen::Vector3d x = axis.normalized();
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ() - x.z() * x;
  if (z.norm() < 1e-6) z = x.unitOrthogonal();
  z.normalize();
  Eigen::Matrix3d frame;
  frame.col(0) = x;
  frame.col(1) = z.cross(x);
  frame.col(2) = z;
  const Eigen::Matrix3d rolled = frame * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return Eigen::Quaternionf(Eigen::Quaterniond(rolled).cast<float>()).normalized();
}

}  // namespace

void FoliageOptions::Validate() const {
  const auto check = [](bool ok, const std::string& field, const std::string& message) {
    CheckOption(ok, "foliage options", field, message);
  };
  check(leaves_per_metre >= 0.0 && std::isfinite(leaves_per_metre), "leaves_per_metre",
        fmt::format("expected >= 0, got {}", leaves_per_metre));
  check(leaf_length_m > 0.0 && std::isfinite(leaf_length_m), "leaf_length_m",
        fmt::format("expected > 0 m, got {}", leaf_length_m));
  check(start_fraction >= 0.0 && start_fraction < 1.0, "start_fraction",
        fmt::format("expected in [0, 1), got {}", start_fraction));
  check(std::isfinite(tilt_rad), "tilt_rad",
        fmt::format("expected a finite angle, got {}", tilt_rad));
  check(size_jitter >= 0.0 && size_jitter < 1.0, "size_jitter",
        fmt::format("expected in [0, 1), got {}", size_jitter));
  check(angle_jitter_rad >= 0.0 && std::isfinite(angle_jitter_rad), "angle_jitter_rad",
        fmt::format("expected a finite angle >= 0, got {}", angle_jitter_rad));
  check(max_leaves >= 0, "max_leaves", fmt::format("expected >= 0, got {}", max_leaves));
}

std::vector<int> NodeOffsets(const Tree& tree) {
  std::vector<int> offsets(tree.branches.size() + 1, 0);
  for (size_t b = 0; b < tree.branches.size(); ++b) {
    offsets[b + 1] = offsets[b] + static_cast<int>(tree.branches[b].nodes.size());
  }
  return offsets;
}

std::vector<LeafInstance> PlaceLeaves(const Tree& tree, float model_length,
                                      const FoliageOptions& options) {
  options.Validate();
  if (!(model_length > 0.0f) || !std::isfinite(model_length)) {
    throw InputError("foliage", "model_length",
                     fmt::format("expected a leaf model of positive length, got {}", model_length));
  }
  const std::vector<int> offsets = NodeOffsets(tree);
  const std::vector<std::vector<int>> children = tree.Children();

  // How many leaves each terminal branch gets, scaled down together to respect the cap.
  std::vector<int> terminal;
  double wanted = 0.0;
  for (const Branch& b : tree.branches) {
    if (!children[b.id].empty() || b.nodes.size() < 2) continue;
    terminal.push_back(b.id);
    wanted += options.leaves_per_metre * b.Length() * (1.0 - options.start_fraction);
  }
  const double keep = wanted > options.max_leaves ? options.max_leaves / wanted : 1.0;

  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  const float base_scale = static_cast<float>(options.leaf_length_m / model_length);
  std::vector<LeafInstance> leaves;
  for (const int id : terminal) {
    const Branch& branch = tree.branches[id];
    const double length = branch.Length();
    const double span = length * (1.0 - options.start_fraction);
    const int count = static_cast<int>(std::floor(options.leaves_per_metre * span * keep + 0.5));
    if (count <= 0) continue;
    const std::vector<double> arcs = branch.ArcLengths();
    double phase = kTwoPi * 0.5 * (unit(rng) + 1.0);
    for (int i = 0; i < count; ++i) {
      // Evenly along the outer part, the last leaf at the tip.
      const double s = length - span * (count == 1 ? 0.0 : static_cast<double>(i) / count);
      const size_t seg = std::min<size_t>(
          std::upper_bound(arcs.begin(), arcs.end(), s) - arcs.begin(), arcs.size() - 1);
      const size_t a = seg == 0 ? 0 : seg - 1;
      const Eigen::Vector3d tangent_raw = branch.nodes[a + 1].position - branch.nodes[a].position;
      const Eigen::Vector3d tangent =
          tangent_raw.norm() > 1e-12 ? Eigen::Vector3d(tangent_raw.normalized()) : branch.frame.v;
      Eigen::Vector3d across = branch.frame.u - branch.frame.u.dot(tangent) * tangent;
      if (across.norm() < 1e-9) across = tangent.unitOrthogonal();
      across.normalize();
      const Eigen::Vector3d across2 = tangent.cross(across);
      phase += golden_angle + options.angle_jitter_rad * unit(rng);
      const Eigen::Vector3d radial = std::cos(phase) * across + std::sin(phase) * across2;
      const double tilt = options.tilt_rad + 0.5 * options.angle_jitter_rad * unit(rng);
      const Eigen::Vector3d axis = std::cos(tilt) * tangent + std::sin(tilt) * radial;

      const Eigen::Vector3d point = branch.PointAt(s);
      const double radius = branch.nodes[a].radius;
      // The node nearest the leaf carries it.
      const size_t node = (a + 1 < arcs.size() && arcs[a + 1] - s < s - arcs[a]) ? a + 1 : a;
      LeafInstance leaf;
      leaf.branch = id;
      leaf.node = offsets[id] + static_cast<int>(node);
      leaf.offset = (point + radius * radial - branch.nodes[node].position).cast<float>();
      leaf.orientation = LeafFrame(axis, options.angle_jitter_rad * unit(rng));
      leaf.scale = base_scale * static_cast<float>(1.0 + options.size_jitter * unit(rng));
      leaves.push_back(leaf);
    }
  }
  return leaves;
}

}  // namespace simtree::viewer
