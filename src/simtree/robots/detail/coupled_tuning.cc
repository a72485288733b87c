#include "simtree/robots/detail/coupled_tuning.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "simtree/core/units.h"
#include "simtree/robots/detail/joint_space_model.h"

namespace simtree::robots::detail {
namespace {

constexpr double kMaxLogStep = 0.5;  // a stiffness scale changes by at most e^0.5 a step

// One branch's hinges of one bending plane, with its targets.
struct Group {
  std::vector<int> hinges;  // indices into JointSpaceModel::hinges
  double omega = 0.0, zeta = 0.0;
};

std::vector<Group> BendingGroups(const Tree& tree, const RobotModel& model,
                                 const std::vector<HingeIndex>& hinges) {
  std::vector<Group> groups;
  for (const Branch& branch : tree.branches) {
    for (HingeKind kind : {HingeKind::kBendU, HingeKind::kBendW}) {
      Group g;
      const Mode& mode =
          branch.material->mode(kind == HingeKind::kBendU ? ModeKind::kBendU : ModeKind::kBendW);
      g.omega = kTwoPi * mode.frequency_hz;
      g.zeta = mode.damping_ratio;
      for (size_t i = 0; i < hinges.size(); ++i) {
        const Segment& s = model.segments[hinges[i].segment];
        if (s.branch == branch.id && s.hinges[hinges[i].hinge].kind == kind) {
          g.hinges.push_back(static_cast<int>(i));
        }
      }
      if (!g.hinges.empty()) groups.push_back(std::move(g));
    }
  }
  return groups;
}

// The tree's modes at the present springs, and each mode's share of strain energy per group.
struct Modes {
  Eigen::VectorXd lambda;  // ascending
  Eigen::MatrixXd phi;     // M-normalised, one mode a column
  Eigen::MatrixXd share;   // [mode][group]: sum over the group's hinges of k phi^2 / lambda
};

bool SolveModes(const JointSpaceModel& lin, const Eigen::VectorXd& k,
                const std::vector<Group>& groups, Modes* out, CoupledTuningReport* report) {
  const Eigen::MatrixXd stiffness = Eigen::MatrixXd(k.asDiagonal()) + lin.gravity;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, lin.mass);
  if (solver.info() != Eigen::Success) return false;
  report->lowest_eigenvalue = solver.eigenvalues()(0);
  report->unstable_modes = static_cast<int>((solver.eigenvalues().array() < 0).count());
  if (!(solver.eigenvalues()(0) > 0)) return false;
  out->lambda = solver.eigenvalues();
  out->phi = solver.eigenvectors();
  const Eigen::MatrixXd strain = (out->phi.cwiseAbs2().transpose() * k.asDiagonal());
  out->share.resize(out->lambda.size(), groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(out->lambda.size());
    for (int i : groups[g].hinges) sum += strain.col(i);
    out->share.col(g) = sum.cwiseQuotient(out->lambda);
  }
  return true;
}

// One mode per group, one group per mode: the strongest claims (share / lambda) first.
std::vector<int> AssignModes(const Modes& modes) {
  std::vector<std::tuple<double, int, int>> claims;  // (weight, mode, group)
  for (int m = 0; m < modes.share.rows(); ++m) {
    for (int g = 0; g < modes.share.cols(); ++g) {
      if (modes.share(m, g) > 0.05) claims.emplace_back(modes.share(m, g) / modes.lambda(m), m, g);
    }
  }
  std::sort(claims.begin(), claims.end(), std::greater<>());
  std::vector<int> mode_of(modes.share.cols(), -1);
  std::vector<bool> taken(modes.share.rows(), false);
  for (const auto& [weight, m, g] : claims) {
    if (mode_of[g] >= 0 || taken[m]) continue;
    mode_of[g] = m;
    taken[m] = true;
  }
  return mode_of;
}

// Rows of the energy shares for the assigned modes: J(g, h) = d log lambda_{mode(g)} / d log s_h.
Eigen::MatrixXd AssignedShares(const Modes& modes, const std::vector<int>& mode_of) {
  Eigen::MatrixXd j(mode_of.size(), modes.share.cols());
  for (size_t g = 0; g < mode_of.size(); ++g) j.row(g) = modes.share.row(mode_of[g]);
  return j;
}

// The damping ratio of every assigned mode (modal, the cross terms of non-proportional damping
// left out: they are second order at these ratios); fills the report's errors.
void Measure(const Modes& modes, const std::vector<int>& mode_of, const std::vector<Group>& groups,
             const Eigen::VectorXd& c, CoupledTuningReport* report) {
  report->worst_frequency_error = report->worst_damping_error = 0.0;
  report->groups_off = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    const int m = mode_of[g];
    const double omega = std::sqrt(modes.lambda(m));
    const double zeta = modes.phi.col(m).cwiseAbs2().dot(c) / (2.0 * omega);
    const double df = std::abs(omega / groups[g].omega - 1.0);
    report->worst_frequency_error = std::max(report->worst_frequency_error, df);
    report->worst_damping_error =
        std::max(report->worst_damping_error, std::abs(zeta / groups[g].zeta - 1.0));
    if (df > 0.05) ++report->groups_off;
  }
  report->omega_max = std::sqrt(modes.lambda(modes.lambda.size() - 1));
}

// Newton's step on the log-stiffness scales, bounded.
Eigen::VectorXd StiffnessStep(const Modes& modes, const std::vector<int>& mode_of,
                              const std::vector<Group>& groups, const Eigen::MatrixXd& jacobian) {
  Eigen::VectorXd residual(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    const double target = groups[g].omega * groups[g].omega;
    residual(g) = std::log(target / std::max(modes.lambda(mode_of[g]), 1e-6 * target));
  }
  Eigen::VectorXd step = jacobian.partialPivLu().solve(residual);
  if (!step.allFinite()) step = residual;
  return step.cwiseMax(-kMaxLogStep).cwiseMin(kMaxLogStep);
}

// Stiffness-proportional factors beta_h giving each assigned mode its group's damping ratio;
// damping of hinges in no group (twist) is kept and counted.
Eigen::VectorXd DampingFactors(const Modes& modes, const std::vector<int>& mode_of,
                               const std::vector<Group>& groups, const Eigen::MatrixXd& jacobian,
                               const Eigen::VectorXd& c_other) {
  Eigen::VectorXd rhs(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    const int m = mode_of[g];
    const double omega = std::sqrt(modes.lambda(m));
    const double other = modes.phi.col(m).cwiseAbs2().dot(c_other);
    rhs(g) = (2.0 * omega * groups[g].zeta - other) / modes.lambda(m);
  }
  Eigen::VectorXd beta = jacobian.partialPivLu().solve(rhs);
  for (size_t g = 0; g < groups.size(); ++g) {
    // Never negative or vanishing: at least a tenth of the group's own chain value.
    const double floor = 0.2 * groups[g].zeta / groups[g].omega;
    if (!std::isfinite(beta(g)) || beta(g) < floor) beta(g) = floor;
  }
  return beta;
}

// Writes the scaled stiffness and the new damping, keeping each spring's torque at rest (it
// balances gravity).
void ApplyToModel(const std::vector<Group>& groups, const std::vector<HingeIndex>& hinges,
                  const Eigen::VectorXd& log_step, const Eigen::VectorXd& beta, RobotModel* model) {
  for (size_t g = 0; g < groups.size(); ++g) {
    for (int i : groups[g].hinges) {
      Hinge& h = model->segments[hinges[i].segment].hinges[hinges[i].hinge];
      const double torque = h.spring_reference * h.stiffness;
      h.stiffness *= std::exp(log_step(g));
      h.damping = beta(g) * h.stiffness;
      h.spring_reference = torque / h.stiffness;
    }
  }
}

}  // namespace

CoupledTuningReport TuneCoupled(const Tree& tree, int max_iterations, double tolerance,
                                double gravity, RobotModel* model) {
  const JointSpaceModel lin = LineariseRobotModel(*model, gravity);
  const int n = static_cast<int>(lin.hinges.size());
  const std::vector<Group> groups = BendingGroups(tree, *model, lin.hinges);
  std::vector<bool> grouped(n, false);
  for (const Group& g : groups) {
    for (int i : g.hinges) grouped[i] = true;
  }
  CoupledTuningReport report;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    Eigen::VectorXd k(n), c(n), c_other = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      const Hinge& h = model->segments[lin.hinges[i].segment].hinges[lin.hinges[i].hinge];
      k(i) = h.stiffness;
      c(i) = h.damping;
      if (!grouped[i]) c_other(i) = h.damping;
    }
    Modes modes;
    if (!SolveModes(lin, k, groups, &modes, &report)) break;
    const std::vector<int> mode_of = AssignModes(modes);
    if (std::count(mode_of.begin(), mode_of.end(), -1) > 0) break;
    Measure(modes, mode_of, groups, c, &report);
    report.iterations = iteration;
    report.converged =
        report.worst_frequency_error < tolerance && report.worst_damping_error < tolerance;
    if (report.converged || iteration == max_iterations) break;
    const Eigen::MatrixXd jacobian = AssignedShares(modes, mode_of);
    const Eigen::VectorXd beta = DampingFactors(modes, mode_of, groups, jacobian, c_other);
    ApplyToModel(groups, lin.hinges, StiffnessStep(modes, mode_of, groups, jacobian), beta, model);
  }
  return report;
}

}  // namespace simtree::robots::detail
