#include "simtree/pipeline/detail/pull_motion_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "simtree/dynamics/live_pull.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::pipeline::detail {
namespace {

// A tracked displacement the fit explains: marker (index into the observations), time, world.
struct Sample {
  int marker = 0;
  double time_s = 0.0;
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
};

std::vector<Sample> TrackedSamples(const Trajectories& tracks,
                                   const Eigen::Isometry3d& world_from_camera,
                                   const std::vector<PullObservation>& observations, double from_s,
                                   double to_s) {
  std::vector<Sample> out;
  for (size_t i = 0; i < observations.size(); ++i) {
    const PullObservation& o = observations[i];
    for (int f = 0; f < tracks.frame_count(); ++f) {
      const double t = tracks.times_s[f];
      if (t < from_s || t > to_s || !o.track->valid[f]) continue;
      out.push_back({static_cast<int>(i), t,
                     world_from_camera.linear() * (o.track->positions[f] - o.rest_camera)});
    }
  }
  return out;
}

// The simulated displacement of every observed marker per newton of the candidate's force
// (along its direction): held still (the static equilibrium), then let go at time 0 and sampled
// after every step of the replay's length (the model's response depends on its step, so it is
// the replay's). Starting from the static hold leaves out whatever the capture's ramp set
// ringing, which no replay knows. The model's motion scales with the force but, measured, does
// not add up over force directions, so the direction is the static fit's (statics do add up)
// and only the size is fitted here.
struct UnitResponse {
  double step_s = 1.0 / 30.0;
  std::vector<std::vector<Eigen::Vector3d>> steps;  // [step][marker]

  // At `since_release_s` (the held shape before 0, linear between steps, held at the end).
  Eigen::Vector3d At(int marker, double since_release_s) const {
    const double x =
        std::clamp(since_release_s / step_s, 0.0, static_cast<double>(steps.size() - 1));
    const auto k = std::min(static_cast<size_t>(x), steps.size() - 2);
    const double w = x - static_cast<double>(k);
    return (1.0 - w) * steps[k][marker] + w * steps[k + 1][marker];
  }
};

std::vector<Eigen::Vector3d> MarkerPositions(const dynamics::TreeDynamics& sim,
                                             const std::vector<PullObservation>& obs) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(obs.size());
  for (const PullObservation& o : obs) out.push_back(sim.PointPosition(o.branch, o.arc_length));
  return out;
}

UnitResponse SimulateUnitResponse(const Tree& tree, const std::vector<PullObservation>& obs,
                                  const PullCandidate& c, double duration_s, double step_s) {
  UnitResponse out;
  out.step_s = step_s;
  dynamics::TreeDynamics sim(tree);
  const std::vector<Eigen::Vector3d> rest = MarkerPositions(sim, obs);
  const double force = c.force.norm();
  dynamics::Rope rope;
  rope.branch = c.branch;
  rope.arc_length = c.arc_length;
  rope.anchor = tree.branches[c.branch].PointAt(c.arc_length) + 1000.0 * c.force.normalized();
  rope.force_n = force;
  sim.AttachRope(rope);
  sim.SettleStatic();
  sim.ReleaseAllRopes();
  const int steps = std::max(2, static_cast<int>(std::ceil(duration_s / step_s)) + 1);
  out.steps.reserve(steps);
  for (int k = 0; k < steps; ++k) {
    if (k > 0) sim.Step(step_s);
    std::vector<Eigen::Vector3d> frame = MarkerPositions(sim, obs);
    for (size_t m = 0; m < frame.size(); ++m) frame[m] = (frame[m] - rest[m]) / force;
    out.steps.push_back(std::move(frame));
  }
  return out;
}

struct ReleaseFit {
  double release_s = 0.0;
  double force_n = 0.0;  // along the candidate's direction
  double squared_residual = std::numeric_limits<double>::infinity();
};

// The force that best explains the used samples with the rope let go at `release_s`.
ReleaseFit FitAtRelease(const UnitResponse& r, const std::vector<Sample>& samples,
                        const std::vector<bool>& used, double release_s) {
  double rr = 0.0, rd = 0.0, dd = 0.0;
  for (const Sample& s : samples) {
    if (!used[s.marker]) continue;
    const Eigen::Vector3d a = r.At(s.marker, s.time_s - release_s);
    rr += a.squaredNorm();
    rd += a.dot(s.displacement);
    dd += s.displacement.squaredNorm();
  }
  ReleaseFit fit;
  fit.release_s = release_s;
  if (rr > 0.0) {
    fit.force_n = rd / rr;
    fit.squared_residual = std::max(0.0, dd - rd * rd / rr);
  }
  return fit;
}

// The best (candidate, release, force) over the used markers. The releases tried are the
// replay's step boundaries within the allowed shift of the detected release: where a replay
// can let go.
struct SearchResult {
  int candidate = -1;
  ReleaseFit fit;
};

SearchResult Search(const std::vector<UnitResponse>& responses, const std::vector<Sample>& samples,
                    const std::vector<bool>& used, double detected_release_s, double max_force_n,
                    const MotionFitOptions& o) {
  SearchResult best;
  for (size_t c = 0; c < responses.size(); ++c) {
    const double step = responses[c].step_s;
    const auto first =
        static_cast<int64_t>(std::ceil((detected_release_s - o.max_release_shift_s) / step - 1e-6));
    const auto last = static_cast<int64_t>(
        std::floor((detected_release_s + o.max_release_shift_s) / step + 1e-6));
    for (int64_t k = std::max<int64_t>(first, 1); k <= last; ++k) {
      const ReleaseFit fit =
          FitAtRelease(responses[c], samples, used, static_cast<double>(k) * step);
      if (!(fit.force_n > 0.0) || fit.force_n > max_force_n ||
          fit.squared_residual >= best.fit.squared_residual) {
        continue;
      }
      best.candidate = static_cast<int>(c);
      best.fit = fit;
    }
  }
  return best;
}

// The markers still used: those whose residual, as a share of their own motion, is within
// `o.outlier_factor` times the median marker's share or within `o.outlier_share`.
std::vector<bool> WithoutOutliers(const UnitResponse& r, const std::vector<Sample>& samples,
                                  const ReleaseFit& fit, size_t markers,
                                  const MotionFitOptions& o) {
  std::vector<double> residual(markers, 0.0), motion(markers, 0.0);
  for (const Sample& s : samples) {
    const Eigen::Vector3d a = r.At(s.marker, s.time_s - fit.release_s);
    residual[s.marker] += (fit.force_n * a - s.displacement).squaredNorm();
    motion[s.marker] += s.displacement.squaredNorm();
  }
  std::vector<double> share(markers, std::numeric_limits<double>::infinity());
  for (size_t m = 0; m < markers; ++m) {
    if (motion[m] > 0) share[m] = std::sqrt(residual[m] / motion[m]);
  }
  std::vector<double> sorted = share;
  std::nth_element(sorted.begin(), sorted.begin() + markers / 2, sorted.end());
  const double limit = std::max(o.outlier_factor * sorted[markers / 2], o.outlier_share);
  std::vector<bool> used(markers);
  for (size_t m = 0; m < markers; ++m) used[m] = share[m] <= limit;
  return used;
}

}  // namespace

MotionFit FitPullOnMotion(const Tree& tree, const Trajectories& tracks,
                          const Eigen::Isometry3d& world_from_camera,
                          const std::vector<PullObservation>& observations,
                          const std::vector<PullCandidate>& candidates, double hold_s,
                          double release_s, double max_force_n, const MotionFitOptions& options) {
  MotionFit out;
  const int frames = tracks.frame_count();
  if (candidates.empty() || observations.empty() || frames < 2) return out;
  const double fps = (frames - 1) / (tracks.times_s.back() - tracks.times_s.front());
  const double end_s = release_s + options.window_s;
  const std::vector<Sample> samples =
      TrackedSamples(tracks, world_from_camera, observations, hold_s, end_s);
  if (samples.empty()) return out;

  // The replay's step: at least ten per frame, so the release falls within a tenth of a frame
  // (3 degrees of phase at 1.3 Hz and 30 fps).
  out.time_step_s =
      dynamics::SplitFrame(1.0 / fps, std::min(dynamics::AutomaticMaxStep(tree), 0.1 / fps)).dt;
  std::vector<UnitResponse> responses;
  for (const PullCandidate& c : candidates) {
    responses.push_back(SimulateUnitResponse(
        tree, observations, c, options.window_s + options.max_release_shift_s + 2.0 / fps,
        out.time_step_s));
  }
  std::vector<bool> used(observations.size(), true);
  SearchResult best = Search(responses, samples, used, release_s, max_force_n, options);
  if (best.candidate < 0) return out;
  used =
      WithoutOutliers(responses[best.candidate], samples, best.fit, observations.size(), options);
  if (std::count(used.begin(), used.end(), true) < static_cast<long>(observations.size())) {
    const SearchResult again = Search(responses, samples, used, release_s, max_force_n, options);
    if (again.candidate >= 0) {
      best = again;
    } else {
      used.assign(observations.size(), true);  // the first fit, on every marker, stands
    }
  }

  out.fitted = true;
  out.candidate = candidates[best.candidate];
  out.candidate.force = best.fit.force_n * out.candidate.force.normalized();
  out.release_s = best.fit.release_s;
  double observed = 0.0;
  for (const Sample& s : samples) {
    if (!used[s.marker]) continue;
    observed += s.displacement.squaredNorm();
    ++out.samples;
  }
  out.markers = static_cast<int>(std::count(used.begin(), used.end(), true));
  out.residual_rms_m = std::sqrt(best.fit.squared_residual / std::max(1, out.samples));
  out.observed_rms_m = std::sqrt(observed / std::max(1, out.samples));
  return out;
}

}  // namespace simtree::pipeline::detail
