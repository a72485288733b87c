#include "simtree/robots/detail/coupled_tuning.h"

#include <algorithm>
#include <cmath>

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
  int branch;
  HingeKind kind;
  std::vector<int> hinges;  // indices into the flat hinge list
  Eigen::Vector3d direction;
  double omega = 0.0, zeta = 0.0;  // targets
};

bool IsAncestorOrSelf(const RobotModel& model, int ancestor, int segment) {
  for (int s = segment; s >= 0; s = model.segments[s].parent) {
    if (s == ancestor) return true;
  }
  return false;
}

}  // namespace

CoupledTuningReport TuneCoupled(const Tree& tree, int max_iterations, double tolerance,
                                RobotModel* model) {
  // The flat hinge list (MuJoCo's dof order does not matter here).
  std::vector<HingeIndex> hinges;
  for (size_t s = 0; s < model->segments.size(); ++s) {
    for (size_t h = 0; h < model->segments[s].hinges.size(); ++h) {
      hinges.push_back({static_cast<int>(s), static_cast<int>(h)});
    }
  }
  const int n = static_cast<int>(hinges.size());
  std::vector<Matrix6d> sub(model->segments.size());
  for (size_t i = 0; i < model->segments.size(); ++i) {
    const Segment& s = model->segments[i];
    sub[i] = SpatialInertia(s.mass_kg, s.center_of_mass, s.inertia);
  }
  for (size_t i = model->segments.size(); i-- > 0;) {
    if (model->segments[i].parent >= 0) sub[model->segments[i].parent] += sub[i];
  }
  std::vector<Vector6d> motion(n);
  for (int i = 0; i < n; ++i) {
    const Segment& s = model->segments[hinges[i].segment];
    motion[i] = HingeMotion(s.hinges[hinges[i].hinge].axis, s.base);
  }
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const int si = hinges[i].segment, sj = hinges[j].segment;
      // Hinges on one path from the root share the bodies beyond the deeper one.
      int deeper = -1;
      if (IsAncestorOrSelf(*model, si, sj)) {
        deeper = sj;
      } else if (IsAncestorOrSelf(*model, sj, si)) {
        deeper = si;
      }
      if (deeper >= 0) mass(i, j) = mass(j, i) = motion[i].dot(sub[deeper] * motion[j]);
    }
  }
  // The groups: every branch's two bending planes, pulled at its tip.
  std::vector<Group> groups;
  for (const Branch& branch : tree.branches) {
    for (HingeKind kind : {HingeKind::kBendU, HingeKind::kBendW}) {
      Group g{branch.id, kind, {}, kind == HingeKind::kBendU ? branch.frame.u : branch.frame.w};
      const Mode& mode =
          branch.material->mode(kind == HingeKind::kBendU ? ModeKind::kBendU : ModeKind::kBendW);
      g.omega = kTwoPi * mode.frequency_hz;
      g.zeta = mode.damping_ratio;
      for (int i = 0; i < n; ++i) {
        const Segment& s = model->segments[hinges[i].segment];
        if (s.branch == branch.id && s.hinges[hinges[i].hinge].kind == kind) g.hinges.push_back(i);
      }
      groups.push_back(std::move(g));
    }
  }
  // Tip displacement along the group's direction per unit hinge rate: the pull's Jacobian row.
  std::vector<Eigen::VectorXd> tip_rows(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    const int tip_segment = model->branch_segments[groups[g].branch].back();
    const Eigen::Vector3d tip = model->segments[tip_segment].tip;
    tip_rows[g] = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      const Segment& s = model->segments[hinges[i].segment];
      if (!IsAncestorOrSelf(*model, hinges[i].segment, tip_segment)) continue;
      const Eigen::Vector3d axis = s.hinges[hinges[i].hinge].axis;
      tip_rows[g](i) = groups[g].direction.dot(axis.cross(tip - s.base));
    }
  }

  CoupledTuningReport report;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    Eigen::VectorXd k(n), c(n);
    for (int i = 0; i < n; ++i) {
      const Hinge& h = model->segments[hinges[i].segment].hinges[hinges[i].hinge];
      k(i) = h.stiffness;
      c(i) = h.damping;
    }
    const Eigen::MatrixXd stiffness = k.asDiagonal();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, mass);
    if (solver.info() != Eigen::Success) break;
    const Eigen::VectorXd& lambda = solver.eigenvalues();
    const Eigen::MatrixXd& phi = solver.eigenvectors();  // M-normalised
    report.omega_max = std::sqrt(lambda(n - 1));
    report.worst_frequency_error = report.worst_damping_error = 0.0;
    report.groups_off = 0;
    std::vector<double> frequency_scale(groups.size()), damping_scale(groups.size());
    for (size_t g = 0; g < groups.size(); ++g) {
      const Eigen::VectorXd tip = phi.transpose() * tip_rows[g];
      int best = 0;
      double best_weight = -1.0;
      for (int m = 0; m < n; ++m) {
        const double weight = tip(m) * tip(m) / lambda(m);
        if (weight > best_weight) best_weight = weight, best = m;
      }
      const double omega = std::sqrt(lambda(best));
      const double zeta = phi.col(best).cwiseAbs2().dot(c) / (2.0 * omega);
      report.worst_frequency_error =
          std::max(report.worst_frequency_error, std::abs(omega / groups[g].omega - 1.0));
      report.worst_damping_error =
          std::max(report.worst_damping_error, std::abs(zeta / groups[g].zeta - 1.0));
      // Half steps, bounded: a branch's mode moves with its neighbours' updates too.
      frequency_scale[g] = std::clamp(groups[g].omega / omega, 0.7, 1.4);
      damping_scale[g] = std::clamp(std::sqrt(groups[g].zeta / zeta), 0.7, 1.4);
      if (std::abs(omega / groups[g].omega - 1.0) > 0.05) ++report.groups_off;
    }
    report.iterations = iteration;
    if (iteration == max_iterations ||
        (report.worst_frequency_error < tolerance && report.worst_damping_error < tolerance)) {
      break;
    }
    for (size_t g = 0; g < groups.size(); ++g) {
      for (int i : groups[g].hinges) {
        Hinge& h = model->segments[hinges[i].segment].hinges[hinges[i].hinge];
        const double torque = h.spring_reference * h.stiffness;  // gravity's, kept
        h.stiffness *= frequency_scale[g];
        // The mode's damping ratio goes as c / omega, and omega as sqrt(k).
        h.damping *= std::sqrt(frequency_scale[g]) * damping_scale[g];
        h.spring_reference = torque / h.stiffness;
      }
    }
  }
  return report;
}

}  // namespace simtree::robots::detail
