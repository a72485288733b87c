#include "simtree/robots/robot_calibration.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/robots/detail/coupled_tuning.h"
#include "simtree/robots/detail/spatial_inertia.h"

namespace simtree::robots {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

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
  double scale = 0.0;      // s: K = s diag(kappa)
  double omega_max = 0.0;  // the chain's highest eigenfrequency at that scale (rad/s)
};

ChainScale SolveChain(const RobotModel& model, const std::vector<Matrix6d>& sub,
                      const std::vector<HingeRef>& hinges, const Eigen::VectorXd& kappa,
                      double omega) {
  const int n = static_cast<int>(hinges.size());
  std::vector<Vector6d> motion(n);
  for (int j = 0; j < n; ++j) {
    const Segment& s = model.segments[hinges[j].segment];
    motion[j] = detail::HingeMotion(s.hinges[hinges[j].hinge].axis, s.base);
  }
  Eigen::MatrixXd mass(n, n);
  for (int j = 0; j < n; ++j) {
    for (int k = j; k < n; ++k) {
      // Both hinges swing the bodies beyond the more distal one.
      mass(j, k) = mass(k, j) = motion[j].dot(sub[hinges[k].segment] * motion[k]);
    }
  }
  const Eigen::MatrixXd stiffness = kappa.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, mass,
                                                                   Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success || !(solver.eigenvalues()(0) > 0)) {
    throw Error(fmt::format("robot export: branch {}: the chain's mass matrix is singular",
                            model.segments[hinges[0].segment].branch));
  }
  ChainScale out;
  out.scale = omega * omega / solver.eigenvalues()(0);
  out.omega_max = std::sqrt(out.scale * solver.eigenvalues()(n - 1));
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
  const ChainScale chain = SolveChain(*model, sub, hinges, kappa, omega);
  const double beta = 2.0 * mode.damping_ratio / omega;  // stiffness-proportional damping
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
  if (options.coupled_iterations > 0 && model->HingeCount() <= options.coupled_max_hinges) {
    const detail::CoupledTuningReport coupled =
        detail::TuneCoupled(tree, options.coupled_iterations, options.coupled_tolerance, model);
    report.coupled = true;
    report.coupled_iterations = coupled.iterations;
    report.worst_frequency_error = coupled.worst_frequency_error;
    report.worst_damping_error = coupled.worst_damping_error;
    report.groups_off = coupled.groups_off;
    omega_max = std::max(omega_max, coupled.omega_max);
  }
  model->gravity = options.gravity;
  model->time_step_s = options.time_step_s > 0
                           ? options.time_step_s
                           : std::min(options.max_time_step_s, options.step_safety / omega_max);
  return report;
}

}  // namespace simtree::robots
