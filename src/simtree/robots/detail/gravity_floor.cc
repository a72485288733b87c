#include "simtree/robots/detail/gravity_floor.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "simtree/robots/detail/joint_space_model.h"

namespace simtree::robots::detail {
namespace {

// A direction of K + G found negative is lifted until it keeps this share of its springs' own
// stiffness: enough that round-off in a simulator does not find it again.
constexpr double kSpringShareKept = 0.05;
constexpr int kMaxCorrections = 50;
// Raises below this share are round-off of the spread, not counted as stiffened hinges.
constexpr double kCountedRaise = 0.01;

Hinge& HingeAt(RobotModel* model, const HingeIndex& index) {
  return model->segments[index.segment].hinges[index.hinge];
}

// Sets the raised stiffness; the spring still balances the same gravity torque at rest.
void ApplyStiffness(const JointSpaceModel& linear, const Eigen::VectorXd& stiffness,
                    GravityFloorReport* report, RobotModel* model) {
  for (size_t i = 0; i < linear.hinges.size(); ++i) {
    Hinge& hinge = HingeAt(model, linear.hinges[i]);
    const double raised = stiffness(static_cast<Eigen::Index>(i));
    if (raised <= hinge.stiffness) continue;
    const double ratio = raised / hinge.stiffness;
    hinge.spring_reference /= ratio;
    hinge.damping *= ratio;
    hinge.stiffness = raised;
    if (ratio > 1.0 + kCountedRaise) ++report->stiffened_hinges;
    report->largest_raise = std::max(report->largest_raise, ratio - 1.0);
  }
}

}  // namespace

GravityFloorReport RaiseGravityFloor(double gravity, int max_hinges, RobotModel* model) {
  GravityFloorReport report;
  if (gravity <= 0 || model->HingeCount() > max_hinges) return report;
  report.checked = true;
  const JointSpaceModel linear = LineariseRobotModel(*model, gravity);
  const Eigen::Index n = static_cast<Eigen::Index>(linear.hinges.size());
  Eigen::VectorXd stiffness(n);
  for (Eigen::Index i = 0; i < n; ++i) stiffness(i) = HingeAt(model, linear.hinges[i]).stiffness;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  for (; report.iterations <= kMaxCorrections; ++report.iterations) {
    solver.compute(Eigen::MatrixXd(linear.gravity) + Eigen::MatrixXd(stiffness.asDiagonal()));
    const Eigen::VectorXd phi = solver.eigenvectors().col(0);
    const Eigen::VectorXd share = phi.cwiseAbs2();
    const double wanted = kSpringShareKept * share.dot(stiffness);
    report.lowest_stiffness_eigenvalue = solver.eigenvalues()(0);
    // A stable tree is left as tuned; an unstable direction is lifted to the margin.
    if (report.lowest_stiffness_eigenvalue >= 0 || report.iterations == kMaxCorrections) break;
    // Each hinge raised in proportion to its own stiffness times its share of phi: lifting phi's
    // Rayleigh quotient to `wanted` with the smallest relative changes.
    const double lift = wanted - report.lowest_stiffness_eigenvalue;
    const Eigen::VectorXd weight = stiffness.cwiseProduct(share);
    stiffness += (lift / weight.dot(share)) * weight;
  }
  ApplyStiffness(linear, stiffness, &report, model);
  return report;
}

}  // namespace simtree::robots::detail
