#include "simtree/robots/step_cost.h"

#include <vector>

namespace simtree::robots {
namespace {

// Seconds per dof and per unit of depth^2: a least-squares fit (relative error) to bench_robots'
// CPU time per step on 12 models, ternary trees of 100-1,000 branches and tree01 at 1-4
// segments with and without twist hinges (2026-11-29); every model within -17%..+9%.
constexpr double kSecondsPerDof = 2.63e-7;
constexpr double kSecondsPerDepthSq = 8.0e-10;

}  // namespace

StepCost EstimateStepCost(const RobotModel& model) {
  StepCost cost;
  // Hinges on the path from the world to each segment's base (its ancestors' hinges).
  std::vector<int> above(model.segments.size(), 0);
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const Segment& segment = model.segments[i];
    if (segment.parent >= 0) {
      above[i] =
          above[segment.parent] + static_cast<int>(model.segments[segment.parent].hinges.size());
    }
    for (size_t h = 0; h < segment.hinges.size(); ++h) {
      const double depth = above[i] + static_cast<double>(h) + 1.0;
      cost.depth_sq_sum += depth * depth;
      ++cost.dofs;
    }
  }
  const double seconds = kSecondsPerDof * cost.dofs + kSecondsPerDepthSq * cost.depth_sq_sum;
  cost.steps_per_second = seconds > 0 ? 1.0 / seconds : 0.0;
  return cost;
}

}  // namespace simtree::robots
