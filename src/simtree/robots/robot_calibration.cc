#include "simtree/robots/robot_calibration.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/robots/detail/coupled_tuning.h"
#include "simtree/robots/detail/gravity_floor.h"
#include "simtree/robots/detail/joint_space_model.h"
#include "simtree/robots/detail/spatial_inertia.h"

namespace simtree::robots {
namespace {

using detail::Matrix6d;
using detail::Vector6d;

// The inertia of every segment's body sub-tree (itself and everything beyond it).
std::vector<Matrix6d> SubtreeInertias(const RobotModel& model) {
  std::vector<Matrix6d> sub(model.segments.size());
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const Segment& s = model.segments[i];
    sub[i] = detail::SpatialInertia(s.mass_kg, s.center_of_mass, s.inertia);
  }
  // Parents come before children: accumulate from the end.
  for (size_t i = model.segments.size(); i-- > 0;) {
    const int parent = model.segments[i].parent;
    if (parent >= 0) sub[parent] += sub[i];
  }
  return sub;
}

struct HingeRef {
  int segment;
  int hinge;
};

// The branch's hinges of one kind, base to tip.
std::vector<HingeRef> HingesOfKind(const RobotModel& model, int branch, HingeKind kind) {
  std::vector<HingeRef> out;
  for (int id : model.branch_segments[branch]) {
    const auto& hinges = model.segments[id].hinges;
    for (size_t h = 0; h < hinges.size(); ++h) {
      if (hinges[h].kind == kind) out.push_back({id, static_cast<int>(h)});
    }
  }
  return out;
}

struct ChainScale {
  double scale = 0.0;      // s: K = s diag(kappa) (+ gravity's stiffness)
  double beta = 0.0;       // stiffness-proportional damping giving the lowest mode its ratio
  double omega_max = 0.0;  // the chain's highest eigenfrequency at that scale (rad/s)
};

struct ChainMatrices {
  Eigen::MatrixXd mass, gravity;
};

// The chain's linearisation over its hinges of one kind, its sub-trees carried rigidly and its
// parent held still.
ChainMatrices LineariseChain(const RobotModel& model, const std::vector<Matrix6d>& sub,
                             const std::vector<HingeRef>& hinges, double gravity) {
  const int n = static_cast<int>(hinges.size());
  std::vector<Vector6d> motion(n);
  for (int j = 0; j < n; ++j) {
    const Segment& s = model.segments[hinges[j].segment];
    motion[j] = detail::HingeMotion(s.hinges[hinges[j].hinge].axis, s.base);
  }
  ChainMatrices out{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, n)};
  for (int j = 0; j < n; ++j) {
    for (int k = j; k < n; ++k) {
      // Both hinges swing the bodies beyond the more distal one (k, base to tip).
      const Segment& distal = model.segments[hinges[k].segment];
      const Matrix6d& carried = sub[hinges[k].segment];
      out.mass(j, k) = out.mass(k, j) = motion[j].dot(carried * motion[k]);
      out.gravity(j, k) = out.gravity(k, j) = detail::GravityStiffness(
          model.segments[hinges[j].segment].hinges[hinges[j].hinge].axis,
          distal.hinges[hinges[k].hinge].axis, distal.base, carried, gravity);
    }
  }
  return out;
}

// s such that the lowest eigenvalue of (s diag(kappa) + G, M) is omega^2: Newton's method on
// s (the lowest eigenvalue is concave and increasing in s, so it converges from any start).
ChainScale SolveChain(const ChainMatrices& chain, const Eigen::VectorXd& kappa, double omega,
                      double zeta, int branch) {
  const int n = static_cast<int>(kappa.size());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      Eigen::MatrixXd(kappa.asDiagonal()), chain.mass, Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success || !(solver.eigenvalues()(0) > 0)) {
    throw Error(
        fmt::format("robot export: branch {}: the chain's mass matrix is singular", branch));
  }
  // From the scale without gravity; never below a twentieth of it (where gravity alone, a
  // hanging pendulum, rings above the target, the chain keeps that much spring).
  const double s_free = omega * omega / solver.eigenvalues()(0);
  double s = s_free;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const Eigen::MatrixXd stiffness = s * Eigen::MatrixXd(kappa.asDiagonal()) + chain.gravity;
    solver.compute(stiffness, chain.mass);
    if (solver.info() != Eigen::Success) {
      throw Error(
          fmt::format("robot export: branch {}: the chain's mass matrix is singular", branch));
    }
    const Eigen::VectorXd phi = solver.eigenvectors().col(0);  // M-normalised
    const double error = omega * omega - solver.eigenvalues()(0);
    if (iteration > 0 && std::abs(error) < 1e-10 * omega * omega) break;
    s = std::max(0.05 * s_free, s + error / phi.cwiseAbs2().dot(kappa));
  }
  ChainScale out;
  out.scale = s;
  // The mode's damping ratio is phi^T C phi / (2 omega) with C = beta s diag(kappa).
  out.beta = 2.0 * zeta * omega / (s * solver.eigenvectors().col(0).cwiseAbs2().dot(kappa));
  out.omega_max = std::sqrt(std::max(solver.eigenvalues()(n - 1), 0.0));
  return out;
}

const Mode& ModeOf(const Material& material, HingeKind kind) {
  switch (kind) {
    case HingeKind::kBendU:
      return material.mode(ModeKind::kBendU);
    case HingeKind::kBendW:
      return material.mode(ModeKind::kBendW);
    case HingeKind::kTwist:
      return material.mode(ModeKind::kTwistV);
  }
  return material.modes[0];
}

// Sets the hinges of one kind on one branch; returns the chain's highest eigenfrequency.
double CalibrateChain(const Branch& branch, HingeKind kind, const std::vector<Matrix6d>& sub,
                      const CalibrationOptions& options, RobotModel* model) {
  const std::vector<HingeRef> hinges = HingesOfKind(*model, branch.id, kind);
  if (hinges.empty()) return 0.0;
  const Mode& mode = ModeOf(*branch.material, kind);
  const double omega = kTwoPi * mode.frequency_hz;
  Eigen::VectorXd kappa(hinges.size());
  const double base_radius = model->segments[hinges[0].segment].radius;
  for (size_t j = 0; j < hinges.size(); ++j) {
    const double r = model->segments[hinges[j].segment].radius;
    kappa(j) = std::pow(r / base_radius, options.stiffness_exponent);
  }
  const ChainScale chain = SolveChain(LineariseChain(*model, sub, hinges, options.gravity), kappa,
                                      omega, mode.damping_ratio, branch.id);
  const double beta = chain.beta;  // stiffness-proportional damping
  const Eigen::Vector3d gravity(0, 0, -options.gravity);
  for (size_t j = 0; j < hinges.size(); ++j) {
    Segment& segment = model->segments[hinges[j].segment];
    Hinge& hinge = segment.hinges[hinges[j].hinge];
    hinge.stiffness = chain.scale * kappa(j);
    hinge.damping = beta * hinge.stiffness;
    // Gravity's torque about the hinge from everything it carries; the spring balances it.
    const Matrix6d& carried = sub[hinges[j].segment];
    const Eigen::Vector3d lever =
        detail::FirstMomentOf(carried) - detail::MassOf(carried) * segment.base;
    const double torque = hinge.axis.dot(lever.cross(gravity));
    hinge.spring_reference = -torque / hinge.stiffness;
  }
  return chain.omega_max;
}

}  // namespace

void CalibrationOptions::Validate() const {
  CheckInRange("stiffness_exponent", stiffness_exponent, 0.0, 8.0);
  CheckNonNegative("gravity", gravity);
  CheckNonNegative("time_step_s", time_step_s);
  CheckInRange("step_safety", step_safety, 1e-3, 1.5);
  CheckAtLeast("coupled_iterations", coupled_iterations, 0);
  CheckAtLeast("coupled_max_hinges", coupled_max_hinges, 0);
  CheckAtLeast("stability_max_hinges", stability_max_hinges, 0);
  CheckInRange("coupled_tolerance", coupled_tolerance, 1e-6, 0.5);
  CheckPositive("max_time_step_s", max_time_step_s);
}

CalibrationReport CalibrateRobotModel(const Tree& tree, const CalibrationOptions& options,
                                      RobotModel* model) {
  options.Validate();
  const std::vector<Matrix6d> sub = SubtreeInertias(*model);
  double omega_max = 0.0;
  for (const Branch& branch : tree.branches) {
    for (HingeKind kind : {HingeKind::kBendU, HingeKind::kBendW, HingeKind::kTwist}) {
      omega_max = std::max(omega_max, CalibrateChain(branch, kind, sub, options, model));
    }
  }
  CalibrationReport report;
  const detail::GravityFloorReport floor =
      detail::RaiseGravityFloor(options.gravity, options.stability_max_hinges, model);
  omega_max *= std::sqrt(1.0 + floor.largest_raise);  // a stiffened hinge rings faster
  report.gravity_checked = floor.checked;
  report.gravity_stiffened_hinges = floor.stiffened_hinges;
  report.gravity_largest_raise = floor.largest_raise;
  report.gravity_lowest_stiffness = floor.lowest_stiffness_eigenvalue;
  if (options.coupled_iterations > 0 && model->HingeCount() <= options.coupled_max_hinges) {
    const detail::CoupledTuningReport coupled = detail::TuneCoupled(
        tree, options.coupled_iterations, options.coupled_tolerance, options.gravity, model);
    report.coupled = true;
    report.coupled_iterations = coupled.iterations;
    report.coupled_converged = coupled.converged;
    report.worst_frequency_error = coupled.worst_frequency_error;
    report.worst_damping_error = coupled.worst_damping_error;
    report.groups_off = coupled.groups_off;
    report.lowest_eigenvalue = coupled.lowest_eigenvalue;
    report.unstable_modes = coupled.unstable_modes;
    omega_max = std::max(omega_max, coupled.omega_max);
  }
  model->gravity = options.gravity;
  model->time_step_s = options.time_step_s > 0
                           ? options.time_step_s
                           : std::min(options.max_time_step_s, options.step_safety / omega_max);
  return report;
}

}  // namespace simtree::robots
