#include "simtree/robots/detail/coupled_tuning.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

#include "simtree/robots/detail/spatial_inertia.h"

namespace simtree::robots::detail {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

struct HingeIndex {
  int segment;
  int hinge;
};

// One branch's hinges of one bending plane and the tip direction a pull in that plane moves.
struct Group {
  int branch = -1;
  HingeKind kind = HingeKind::kBendU;
  std::vector<int> hinges;  // indices into the flat hinge list
  Eigen::Vector3d direction;
  double omega = 0.0, zeta = 0.0;  // targets
  Eigen::VectorXd tip_row;         // tip displacement along `direction` per unit hinge rate
  double frequency_scale = 1.0, damping_scale = 1.0;  // the next update
};

bool IsAncestorOrSelf(const RobotModel& model, int ancestor, int segment) {
  for (int s = segment; s >= 0; s = model.segments[s].parent) {
    if (s == ancestor) return true;
  }
  return false;
}

// The flat hinge list (MuJoCo's dof order does not matter here).
std::vector<HingeIndex> FlatHinges(const RobotModel& model) {
  std::vector<HingeIndex> hinges;
  for (size_t s = 0; s < model.segments.size(); ++s) {
    for (size_t h = 0; h < model.segments[s].hinges.size(); ++h) {
      hinges.push_back({static_cast<int>(s), static_cast<int>(h)});
    }
  }
  return hinges;
}

// The joint-space mass matrix about the rest pose: each segment's spatial inertia with its
// sub-tree's, seen through every pair of hinges on one path from the root.
Eigen::MatrixXd JointSpaceMass(const RobotModel& model, const std::vector<HingeIndex>& hinges) {
  const int n = static_cast<int>(hinges.size());
  std::vector<Matrix6d> sub(model.segments.size());
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const Segment& s = model.segments[i];
    sub[i] = SpatialInertia(s.mass_kg, s.center_of_mass, s.inertia);
  }
  for (size_t i = model.segments.size(); i-- > 0;) {
    if (model.segments[i].parent >= 0) sub[model.segments[i].parent] += sub[i];
  }
  std::vector<Vector6d> motion(n);
  for (int i = 0; i < n; ++i) {
    const Segment& s = model.segments[hinges[i].segment];
    motion[i] = HingeMotion(s.hinges[hinges[i].hinge].axis, s.base);
  }
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const int si = hinges[i].segment, sj = hinges[j].segment;
      // Hinges on one path from the root share the bodies beyond the deeper one.
      int deeper = -1;
      if (IsAncestorOrSelf(model, si, sj)) {
        deeper = sj;
      } else if (IsAncestorOrSelf(model, sj, si)) {
        deeper = si;
      }
      if (deeper >= 0) mass(i, j) = mass(j, i) = motion[i].dot(sub[deeper] * motion[j]);
    }
  }
  return mass;
}

// Every branch's two bending planes with their targets, each with its tip-pull row: the tip's
// displacement along the plane's direction per unit hinge rate.
std::vector<Group> BendingGroups(const Tree& tree, const RobotModel& model,
                                 const std::vector<HingeIndex>& hinges) {
  const int n = static_cast<int>(hinges.size());
  std::vector<Group> groups;
  for (const Branch& branch : tree.branches) {
    for (HingeKind kind : {HingeKind::kBendU, HingeKind::kBendW}) {
      Group g;
      g.branch = branch.id;
      g.kind = kind;
      g.direction = kind == HingeKind::kBendU ? branch.frame.u : branch.frame.w;
      const Mode& mode =
          branch.material->mode(kind == HingeKind::kBendU ? ModeKind::kBendU : ModeKind::kBendW);
      g.omega = kTwoPi * mode.frequency_hz;
      g.zeta = mode.damping_ratio;
      const int tip_segment = model.branch_segments[branch.id].back();
      const Eigen::Vector3d tip = model.segments[tip_segment].tip;
      g.tip_row = Eigen::VectorXd::Zero(n);
      for (int i = 0; i < n; ++i) {
        const Segment& s = model.segments[hinges[i].segment];
        const Hinge& h = s.hinges[hinges[i].hinge];
        if (s.branch == branch.id && h.kind == kind) g.hinges.push_back(i);
        if (IsAncestorOrSelf(model, hinges[i].segment, tip_segment)) {
          g.tip_row(i) = g.direction.dot(h.axis.cross(tip - s.base));
        }
      }
      groups.push_back(std::move(g));
    }
  }
  return groups;
}

// Each group's frequency and damping scales from the tree's modes at the present stiffness and
// damping: the mode its tip pull rings in (largest (tip displacement)^2 / eigenvalue) against the
// group's target. Fills the report's errors; false when the eigenproblem fails.
bool MeasureGroups(const Eigen::MatrixXd& mass, const Eigen::VectorXd& k, const Eigen::VectorXd& c,
                   std::vector<Group>& groups, CoupledTuningReport& report) {
  const int n = static_cast<int>(k.size());
  const Eigen::MatrixXd stiffness = k.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, mass);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::VectorXd& lambda = solver.eigenvalues();
  const Eigen::MatrixXd& phi = solver.eigenvectors();  // M-normalised
  report.omega_max = std::sqrt(lambda(n - 1));
  report.worst_frequency_error = report.worst_damping_error = 0.0;
  report.groups_off = 0;
  for (Group& g : groups) {
    const Eigen::VectorXd tip = phi.transpose() * g.tip_row;
    int best = 0;
    double best_weight = -1.0;
    for (int m = 0; m < n; ++m) {
      const double weight = tip(m) * tip(m) / lambda(m);
      if (weight > best_weight) best_weight = weight, best = m;
    }
    const double omega = std::sqrt(lambda(best));
    const double zeta = phi.col(best).cwiseAbs2().dot(c) / (2.0 * omega);
    report.worst_frequency_error =
        std::max(report.worst_frequency_error, std::abs(omega / g.omega - 1.0));
    report.worst_damping_error =
        std::max(report.worst_damping_error, std::abs(zeta / g.zeta - 1.0));
    // Half steps, bounded: a branch's mode moves with its neighbours' updates too.
    g.frequency_scale = std::clamp(g.omega / omega, 0.7, 1.4);
    g.damping_scale = std::clamp(std::sqrt(g.zeta / zeta), 0.7, 1.4);
    if (std::abs(omega / g.omega - 1.0) > 0.05) ++report.groups_off;
  }
  return true;
}

// Scales each group's hinges, keeping gravity's torque at the rest pose.
void ApplyScales(const std::vector<Group>& groups, const std::vector<HingeIndex>& hinges,
                 RobotModel* model) {
  for (const Group& g : groups) {
    for (int i : g.hinges) {
      Hinge& h = model->segments[hinges[i].segment].hinges[hinges[i].hinge];
      const double torque = h.spring_reference * h.stiffness;
      h.stiffness *= g.frequency_scale;
      // The mode's damping ratio goes as c / omega, and omega as sqrt(k).
      h.damping *= std::sqrt(g.frequency_scale) * g.damping_scale;
      h.spring_reference = torque / h.stiffness;
    }
  }
}

}  // namespace

CoupledTuningReport TuneCoupled(const Tree& tree, int max_iterations, double tolerance,
                                RobotModel* model) {
  const std::vector<HingeIndex> hinges = FlatHinges(*model);
  const int n = static_cast<int>(hinges.size());
  const Eigen::MatrixXd mass = JointSpaceMass(*model, hinges);
  std::vector<Group> groups = BendingGroups(tree, *model, hinges);
  CoupledTuningReport report;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    Eigen::VectorXd k(n), c(n);
    for (int i = 0; i < n; ++i) {
      const Hinge& h = model->segments[hinges[i].segment].hinges[hinges[i].hinge];
      k(i) = h.stiffness;
      c(i) = h.damping;
    }
    if (!MeasureGroups(mass, k, c, groups, report)) break;
    report.iterations = iteration;
    if (iteration == max_iterations ||
        (report.worst_frequency_error < tolerance && report.worst_damping_error < tolerance)) {
      break;
    }
    ApplyScales(groups, hinges, model);
  }
  return report;
}

}  // namespace simtree::robots::detail
