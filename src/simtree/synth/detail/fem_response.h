#pragma once
// Responses of the FEM oracle: static deflection K x = f, and motion M a + C v + K x = f(t) by
// Newmark's average-acceleration rule (beta = 1/4, gamma = 1/2: unconditionally stable, no
// numerical damping, period error about (omega dt)^2 / 12).
//
// Two integrators give the same Newmark solution:
//   - direct: the whole system, the effective stiffness K + (2/dt) C + (4/dt^2) M factorised once
//     per time step length. It is the reference; its cost grows with the degrees of freedom.
//   - modal: each mode of a ModalBasis integrated by the same rule (exactly the direct solution
//     restricted to those modes, as C is proportional), plus the quasi-static response of every
//     mode left out (K^-1 f - Phi Omega^-2 Phi^T f: the mode-acceleration method), so a held
//     load deflects the tree as the static solve does. The modes above the basis respond
//     instantly rather than ringing; with modes up to tens of hertz that is invisible at 30 fps.
//     It is what a large tree needs: a few hundred thousand scalar steps instead of thousands of
//     sparse solves.
//
// Time steps land exactly on the load's jumps (the rope is cut at `release_s`: steps are
// re-planned there and the acceleration is re-solved from equilibrium with the new load), and
// states at the requested sample times are interpolated within a step with Newmark's own
// constant-average-acceleration assumption. States are handed to a callback in sample order, so
// a 15 s, 450-frame pull test never holds them all: the direct integrator hands each out at once,
// the modal one in batches of 32 (one product of the shape matrix with 32 samples' modal
// coordinates reads the shapes once instead of 32 times).

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/ground_truth.h"
#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/fem_modes.h"

namespace simtree::synth {

// Displacement, velocity and acceleration over the free degrees of freedom at one instant.
struct FemState {
  double time_s = 0.0;
  Eigen::VectorXd x, v, a;
};
// At rest (all zero) at time t.
FemState RestState(const FemModel& model, double time_s = 0.0);

// A load of fixed shape and varying size: f(t) = pattern * scale(t).
struct FemLoad {
  Eigen::VectorXd pattern;              // empty: no load
  std::function<double(double)> scale;  // of time (s); empty: 1
  std::vector<double> jumps_s;          // where scale jumps (time steps land on them)
  double ScaleAt(double t) const { return scale ? scale(t) : 1.0; }
};

struct NewmarkOptions {
  // The longest time step (s); each stretch between jumps takes equal steps no longer than this.
  double max_time_step_s = 1.0 / 600.0;
  // Modal integrator only: also hand out v and a at samples (x always).
  bool sample_rates = true;
};

struct NewmarkResult {
  FemState final_state;  // at the last sample time
  int64_t steps = 0;
  double time_step_s = 0.0;  // of the last stretch
};

// Called at every sample time in order: index into the sample times, the time, the state.
using FemSampleCallback = std::function<void(int, double, const FemState&)>;

// K x = f. Throws InputError for a vector of the wrong size or with NaN.
Eigen::VectorXd SolveStatic(const FemModel& model, const Eigen::VectorXd& force);

// Direct integration from `start` (its acceleration is re-solved from equilibrium) to the last
// sample time. Sample times must be finite, ascending and not before start.time_s.
NewmarkResult IntegrateNewmark(const FemModel& model, const FemState& start, const FemLoad& load,
                               std::span<const double> sample_times, const NewmarkOptions& options,
                               const FemSampleCallback& on_sample);
// The same through the modes (and the static residual of the ones left out). The start state is
// projected on the modes.
NewmarkResult IntegrateNewmark(const FemModel& model, const ModalBasis& modes,
                               const FemState& start, const FemLoad& load,
                               std::span<const double> sample_times, const NewmarkOptions& options,
                               const FemSampleCallback& on_sample);

// The rope of a pull test as an FemLoad: PullLoad::ForceAt along the rest direction from the
// attach point to the anchor, at (branch, arc_length), cut at release_s. Throws InputError for an
// unknown branch, times out of order, a force that is negative or not finite, or an anchor on
// the attach point.
FemLoad PullFemLoad(const FemModel& model, const PullLoad& pull);

struct PullResult {
  FemState release_state;  // at release_s, the instant the rope is cut
  NewmarkResult run;
};
// The pull test from rest at t = 0: ramp, hold, release, free decay, sampled at `sample_times`
// (the camera's frame times). Direct, or through `modes` (see above).
PullResult IntegratePull(const FemModel& model, const PullLoad& pull,
                         std::span<const double> sample_times, const NewmarkOptions& options,
                         const FemSampleCallback& on_sample);
PullResult IntegratePull(const FemModel& model, const ModalBasis& modes, const PullLoad& pull,
                         std::span<const double> sample_times, const NewmarkOptions& options,
                         const FemSampleCallback& on_sample);

// Free vibration from a given state (no load), e.g. a RandomVibrationState.
NewmarkResult IntegrateFree(const FemModel& model, const ModalBasis& modes, const FemState& start,
                            std::span<const double> sample_times, const NewmarkOptions& options,
                            const FemSampleCallback& on_sample);

// "Small branch vibration between views": a random superposition of the lowest `mode_count`
// modes with random phases and amplitudes falling as 1/omega, scaled so that the node that moves
// most is `amplitude_m` from rest. Deterministic in `seed`.
struct VibrationOptions {
  double amplitude_m = 0.003;
  int mode_count = 6;
  uint64_t seed = 1;
};
FemState RandomVibrationState(const FemModel& model, const ModalBasis& modes,
                              const VibrationOptions& options);

// 1/2 v^T M v + 1/2 x^T K x (J).
double MechanicalEnergy(const FemModel& model, const FemState& state);

}  // namespace simtree::synth
