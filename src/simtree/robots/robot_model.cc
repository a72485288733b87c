#include "simtree/robots/robot_model.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"

namespace simtree::robots {
namespace {

const char* HingeSuffix(HingeKind kind) {
  switch (kind) {
    case HingeKind::kBendU:
      return "bu";
    case HingeKind::kBendW:
      return "bw";
    case HingeKind::kTwist:
      return "tw";
  }
  return "?";
}

// Radius at arc length s, linear between nodes.
double RadiusAt(const Branch& branch, const std::vector<double>& arcs, double s) {
  const auto it = std::upper_bound(arcs.begin(), arcs.end(), s);
  if (it == arcs.begin()) return branch.nodes.front().radius;
  if (it == arcs.end()) return branch.nodes.back().radius;
  const size_t i = static_cast<size_t>(it - arcs.begin());
  const double span = arcs[i] - arcs[i - 1];
  const double t = span > 0 ? (s - arcs[i - 1]) / span : 0.0;
  return branch.nodes[i - 1].radius * (1 - t) + branch.nodes[i].radius * t;
}

void CheckTree(const Tree& tree, const std::string& source) {
  ValidationOptions validation;
  validation.require_materials = true;
  Validate(tree, source, validation);
  for (const Branch& branch : tree.branches) {
    const double length = branch.Length();
    if (!(length > 1e-6)) {
      throw InputError(source, fmt::format("branches[{}]", branch.id),
                       fmt::format("expected a branch of positive length, got {} m", length));
    }
  }
}

// Mass, centre of mass and inertia of the wood between arc lengths a and b, as a rod along the
// chord from `base` to `tip` (5-point Gauss-Legendre along the arc for the taper).
void FillMass(const Branch& branch, const std::vector<double>& arcs, double density,
              Segment* segment) {
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  const double a = segment->arc_begin, b = segment->arc_end;
  const double half = 0.5 * (b - a);
  double mass = 0.0, first_moment = 0.0, r2_mass = 0.0;
  for (int q = 0; q < 5; ++q) {
    const double t = 0.5 * (kNodes[q] + 1.0);  // along the segment, 0..1
    const double r = RadiusAt(branch, arcs, a + t * (b - a));
    const double dm = density * kPi * r * r * kWeights[q] * half;
    mass += dm;
    first_moment += dm * t;
    r2_mass += dm * r * r;
  }
  const Eigen::Vector3d chord = segment->tip - segment->base;
  const double length = chord.norm();
  const Eigen::Vector3d axis = chord / length;
  const double t_com = mass > 0 ? first_moment / mass : 0.5;
  segment->mass_kg = mass;
  segment->center_of_mass = segment->base + t_com * chord;
  // A rod: m r^2 / 2 about its axis, m (3 r^2 + L^2) / 12 across it.
  const double r2 = mass > 0 ? r2_mass / mass : 0.0;
  const double axial = 0.5 * mass * r2;
  const double across = mass * (3.0 * r2 + length * length) / 12.0;
  const Eigen::Matrix3d along = axis * axis.transpose();
  segment->inertia = axial * along + across * (Eigen::Matrix3d::Identity() - along);
}

int SegmentsPerBranch(const Tree& tree, const RobotModelOptions& options) {
  int per_branch = options.segments_per_branch;
  if (options.max_bodies > 0) {
    per_branch = std::min(per_branch, std::max(1, options.max_bodies / tree.size()));
  }
  return per_branch;
}

bool WantsTwist(const RobotModelOptions& options, bool has_children) {
  switch (options.twist) {
    case TwistHinges::kNone:
      return false;
    case TwistHinges::kBranchesWithKids:
      return has_children;
    case TwistHinges::kAll:
      return true;
  }
  return false;
}

void AddSegments(const Tree& tree, const Branch& branch, const RobotModelOptions& options,
                 int per_branch, bool twist, RobotModel* model) {
  const std::vector<double> arcs = branch.ArcLengths();
  const double length = arcs.back();
  int parent = -1;
  if (!branch.is_trunk()) {
    const Branch& parent_branch = tree.branches[branch.parent];
    parent = SegmentAt(*model, branch.parent, parent_branch.ArcLengths()[branch.parent_node]);
  }
  std::vector<int>& ids = model->branch_segments[branch.id];
  for (int i = 0; i < per_branch; ++i) {
    Segment segment;
    segment.name = fmt::format("b{}_s{}", branch.id, i);
    segment.branch = branch.id;
    segment.index = i;
    segment.parent = i == 0 ? parent : ids.back();
    segment.arc_begin = length * i / per_branch;
    segment.arc_end = length * (i + 1) / per_branch;
    segment.base = branch.PointAt(segment.arc_begin);
    segment.tip = branch.PointAt(segment.arc_end);
    if ((segment.tip - segment.base).norm() < 1e-9) {
      // A polyline folding back on itself: keep the branch's own direction.
      segment.tip = segment.base + branch.frame.v * (segment.arc_end - segment.arc_begin);
    }
    FillMass(branch, arcs, options.wood_density_kg_m3, &segment);
    segment.radius = std::sqrt(segment.mass_kg / (options.wood_density_kg_m3 * kPi *
                                                  (segment.arc_end - segment.arc_begin)));
    const Eigen::Vector3d axis = (segment.tip - segment.base).normalized();
    // bend_u deflects along u: a turn about w (and bend_w about u), as the modal model's modes.
    segment.hinges.push_back({HingeKind::kBendU, "", branch.frame.w.normalized()});
    segment.hinges.push_back({HingeKind::kBendW, "", branch.frame.u.normalized()});
    if (twist) segment.hinges.push_back({HingeKind::kTwist, "", axis});
    for (Hinge& hinge : segment.hinges) {
      hinge.name = fmt::format("{}_{}", segment.name, HingeSuffix(hinge.kind));
    }
    model->total_mass_kg += segment.mass_kg;
    ids.push_back(static_cast<int>(model->segments.size()));
    model->segments.push_back(std::move(segment));
  }
}

void AddSites(const Tree& tree, RobotModel* model) {
  for (const Branch& branch : tree.branches) {
    const double length = branch.Length();
    // The grasp point: midway, where a gripper closes on a branch without bending it much.
    const double grasp = 0.5 * length;
    model->sites.push_back({Site::Kind::kGrasp, fmt::format("grasp_b{}", branch.id),
                            SegmentAt(*model, branch.id, grasp), branch.id, -1,
                            branch.PointAt(grasp)});
    model->sites.push_back({Site::Kind::kTip, fmt::format("tip_b{}", branch.id),
                            model->branch_segments[branch.id].back(), branch.id, -1,
                            branch.tip().position});
  }
  for (const Marker& marker : tree.markers) {
    const Branch& branch = tree.branches[marker.branch];
    model->sites.push_back({Site::Kind::kMarker, fmt::format("marker_{}", marker.id),
                            SegmentAt(*model, marker.branch, marker.arc_length), marker.branch,
                            marker.id, branch.PointAt(marker.arc_length)});
  }
}

}  // namespace

const char* ToString(TwistHinges twist) {
  switch (twist) {
    case TwistHinges::kNone:
      return "none";
    case TwistHinges::kBranchesWithKids:
      return "auto";
    case TwistHinges::kAll:
      return "all";
  }
  return "?";
}

TwistHinges ParseTwistHinges(const std::string& text, const std::string& where) {
  if (text == "none") return TwistHinges::kNone;
  if (text == "auto") return TwistHinges::kBranchesWithKids;
  if (text == "all") return TwistHinges::kAll;
  throw InputError(where, "", "expected none, auto or all, got '" + text + "'");
}

void RobotModelOptions::Validate() const {
  CheckAtLeast("segments_per_branch", segments_per_branch, 1);
  CheckAtLeast("max_bodies", max_bodies, 0);
  CheckPositive("wood_density_kg_m3", wood_density_kg_m3);
}

int RobotModel::HingeCount() const {
  int count = 0;
  for (const Segment& segment : segments) count += static_cast<int>(segment.hinges.size());
  return count;
}

const Site* RobotModel::FindSite(const std::string& name) const {
  for (const Site& site : sites) {
    if (site.name == name) return &site;
  }
  return nullptr;
}

int SegmentAt(const RobotModel& model, int branch, double arc_length) {
  const std::vector<int>& ids = model.branch_segments.at(branch);
  for (int id : ids) {
    if (arc_length < model.segments[id].arc_end) return id;
  }
  return ids.back();
}

RobotModel BuildRobotModel(const Tree& tree, const RobotModelOptions& options,
                           const std::string& source) {
  options.Validate();
  CheckTree(tree, source);
  RobotModel model;
  model.segments_per_branch = SegmentsPerBranch(tree, options);
  model.collidable = options.collidable;
  model.branch_segments.resize(tree.size());
  const std::vector<std::vector<int>> children = tree.Children();
  // Parents have smaller ids than their children, so id order puts parents first.
  for (const Branch& branch : tree.branches) {
    AddSegments(tree, branch, options, model.segments_per_branch,
                WantsTwist(options, !children[branch.id].empty()), &model);
  }
  AddSites(tree, &model);
  return model;
}

}  // namespace simtree::robots
