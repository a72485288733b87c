#include "simtree/dynamics/rope.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"

namespace simtree::dynamics {
namespace {

// Tangent of the branch polyline at arc length s.
Eigen::Vector3d TangentAt(const Branch& branch, double s) {
  double remaining = s;
  for (size_t i = 1; i < branch.nodes.size(); ++i) {
    const Eigen::Vector3d d = branch.nodes[i].position - branch.nodes[i - 1].position;
    const double len = d.norm();
    if ((remaining <= len || i + 1 == branch.nodes.size()) && len > 0.0) return d / len;
    remaining -= len;
  }
  return branch.frame.v;
}

}  // namespace

const char* ToString(Rope::Mode mode) {
  return mode == Rope::Mode::kForce ? "force" : "displacement";
}

double ValidateRope(const Tree& tree, const Rope& rope, const std::string& source) {
  if (rope.branch < 0 || rope.branch >= tree.size()) {
    throw InputError(
        source, "branch",
        fmt::format("expected a branch id in [0, {}], got {}", tree.size() - 1, rope.branch));
  }
  const double length = tree.branches[rope.branch].Length();
  if (!std::isfinite(rope.arc_length) || rope.arc_length > length * (1.0 + 1e-9) + 1e-9) {
    throw InputError(source, "arc_length",
                     fmt::format("expected an arc length in [0, {:.6g}] m (the length of branch "
                                 "{}), or a negative value for its tip, got {}",
                                 length, rope.branch, rope.arc_length));
  }
  if (!rope.anchor.allFinite()) {
    throw InputError(source, "anchor", "expected finite anchor coordinates");
  }
  if (!std::isfinite(rope.force_n) || rope.force_n < 0.0) {
    throw InputError(source, "force_n",
                     fmt::format("expected a tension >= 0 N, got {}", rope.force_n));
  }
  if (!std::isfinite(rope.displacement_m) || rope.displacement_m < 0.0) {
    throw InputError(source, "displacement_m",
                     fmt::format("expected a displacement >= 0 m, got {}", rope.displacement_m));
  }
  return rope.arc_length < 0.0 ? length : std::min(rope.arc_length, length);
}

PullTarget ParsePullTarget(const std::string& text, const std::string& where) {
  const auto fail = [&] {
    throw InputError("", where,
                     fmt::format("expected BRANCH or BRANCH@S (a branch id, optionally the arc "
                                 "length in metres from its base), got \"{}\"",
                                 text));
  };
  PullTarget target;
  const size_t at = text.find('@');
  const std::string id_text = text.substr(0, at);
  const char* end = id_text.data() + id_text.size();
  auto [ptr, ec] = std::from_chars(id_text.data(), end, target.branch);
  if (id_text.empty() || ec != std::errc() || ptr != end || target.branch < 0) fail();
  if (at != std::string::npos) {
    const std::string s_text = text.substr(at + 1);
    const char* s_end = s_text.data() + s_text.size();
    auto [s_ptr, s_ec] = std::from_chars(s_text.data(), s_end, target.arc_length);
    if (s_text.empty() || s_ec != std::errc() || s_ptr != s_end ||
        !std::isfinite(target.arc_length) || target.arc_length < 0.0) {
      fail();
    }
  }
  return target;
}

Eigen::Vector3d DefaultPullDirection(const Tree& tree, int branch, double arc_length) {
  const Branch& b = tree.branches.at(branch);
  const double s = arc_length < 0.0 ? b.Length() : arc_length;
  const Eigen::Vector3d tangent = TangentAt(b, s);
  const Eigen::Vector3d down(0, 0, -1);
  Eigen::Vector3d d = down - down.dot(tangent) * tangent;
  // Within ~25 degrees of vertical, pulling down mostly compresses the branch: pull sideways.
  if (d.norm() > 0.42) return d.normalized();
  const Eigen::Vector3d point = b.PointAt(s);
  const Eigen::Vector3d trunk_base = tree.trunk().base().position;
  d = Eigen::Vector3d(point.x() - trunk_base.x(), point.y() - trunk_base.y(), 0.0);
  d -= d.dot(tangent) * tangent;
  if (d.norm() > 1e-6) return d.normalized();
  d = Eigen::Vector3d::UnitX() - tangent.x() * tangent;
  return d.norm() > 1e-6 ? d.normalized() : Eigen::Vector3d(tangent.unitOrthogonal());
}

}  // namespace simtree::dynamics
