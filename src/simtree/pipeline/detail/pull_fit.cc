#include "simtree/pipeline/detail/pull_fit.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::pipeline::detail {
namespace {

constexpr const char* kSource = "pull fit options";

// Mean of the valid positions with time in [t0, t1]; false when there is none.
bool MeanPosition(const Trajectories& tracks, const MarkerTrack& track, double t0, double t1,
                  Eigen::Vector3d& mean) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int f = 0; f < tracks.frame_count(); ++f) {
    const double t = tracks.times_s[f];
    if (t < t0 || t > t1 || !track.valid[f]) continue;
    sum += track.positions[f];
    ++n;
  }
  if (n == 0) return false;
  mean = sum / n;
  return true;
}

std::vector<PullObservation> Observe(const Tree& tree, const Trajectories& tracks,
                                     const Eigen::Isometry3d& world_from_camera, double release_s,
                                     const std::vector<int>& excluded, const PullFitOptions& o) {
  const double start = tracks.times_s.front();
  const double held_end = release_s - o.release_margin_s;
  std::vector<PullObservation> out;
  for (const Marker& m : tree.markers) {
    if (std::find(excluded.begin(), excluded.end(), m.id) != excluded.end()) continue;
    const MarkerTrack* track = tracks.Find(m.id);
    if (!track) continue;
    PullObservation obs{m.branch, m.arc_length, Eigen::Vector3d::Zero(), track, {}};
    Eigen::Vector3d held;
    if (!MeanPosition(tracks, *track, start, start + o.rest_s, obs.rest_camera) ||
        !MeanPosition(tracks, *track, held_end - o.held_window_s, held_end, held)) {
      continue;
    }
    obs.held = world_from_camera.linear() * (held - obs.rest_camera);
    out.push_back(obs);
  }
  return out;
}

// The rope points tried: `arc_samples` along every branch up to `max_level`.
std::vector<std::pair<int, double>> Candidates(const Tree& tree, const PullFitOptions& o) {
  std::vector<std::pair<int, double>> out;
  for (const Branch& b : tree.branches) {
    if (b.level > o.max_level) continue;
    for (int k = 0; k < o.arc_samples; ++k) {
      const double share = (k + 0.5) / o.arc_samples;
      out.emplace_back(
          b.id, (o.min_arc_share + share * (o.max_arc_share - o.min_arc_share)) * b.Length());
    }
  }
  return out;
}

// The static displacement (3 rows each) per newton along x, y and z at the rope point: of every
// marker, then of the rope point itself (the last 3 rows).
Eigen::MatrixXd Compliance(dynamics::TreeDynamics& sim, const std::vector<PullObservation>& obs,
                           int branch, double arc_length) {
  Eigen::MatrixXd c(3 * obs.size() + 3, 3);
  const Eigen::Vector3d point = sim.tree().branches[branch].PointAt(arc_length);
  for (int axis = 0; axis < 3; ++axis) {
    sim.Reset();
    dynamics::Rope rope;
    rope.branch = branch;
    rope.arc_length = arc_length;
    rope.anchor = point + 1000.0 * Eigen::Vector3d::Unit(axis);
    rope.force_n = 1.0;
    sim.AttachRope(rope);
    sim.SettleStatic();
    for (size_t i = 0; i < obs.size(); ++i) {
      const Eigen::Vector3d rest = sim.tree().branches[obs[i].branch].PointAt(obs[i].arc_length);
      c.block<3, 1>(3 * i, axis) = sim.PointPosition(obs[i].branch, obs[i].arc_length) - rest;
    }
    c.block<3, 1>(3 * obs.size(), axis) = sim.PointPosition(branch, arc_length) - point;
  }
  return c;
}

// When the most-moved marker first reaches `fraction` of its held displacement.
double HoldStart(const Trajectories& tracks, const std::vector<PullObservation>& obs,
                 const Eigen::Isometry3d& world_from_camera, double release_s, double fraction) {
  const auto most = std::max_element(obs.begin(), obs.end(), [](const auto& a, const auto& b) {
    return a.held.norm() < b.held.norm();
  });
  const double target = fraction * most->held.norm();
  for (int f = 0; f < tracks.frame_count() && tracks.times_s[f] < release_s; ++f) {
    if (!most->track->valid[f]) continue;
    const Eigen::Vector3d d =
        world_from_camera.linear() * (most->track->positions[f] - most->rest_camera);
    if (d.norm() >= target) return tracks.times_s[f];
  }
  return 0.8 * release_s;
}

// Every candidate rope point whose least-squares force explains the held displacements within
// the limits, best (smallest residual) first.
std::vector<PullCandidate> RankCandidates(const Tree& tree, const std::vector<PullObservation>& obs,
                                          const Eigen::VectorXd& held, const PullFitOptions& o) {
  dynamics::TreeDynamics sim(tree);
  double largest = 0.0;
  for (const PullObservation& ob : obs) largest = std::max(largest, ob.held.norm());
  const auto rows = static_cast<Eigen::Index>(held.size());
  std::vector<PullCandidate> out;
  for (const auto& [branch, arc] : Candidates(tree, o)) {
    const Eigen::MatrixXd all = Compliance(sim, obs, branch, arc);
    const Eigen::MatrixXd c = all.topRows(rows);
    const Eigen::Vector3d force = c.colPivHouseholderQr().solve(held);
    const double point_moves = (all.bottomRows(3) * force).norm();
    if (!force.allFinite() || force.norm() > o.max_force_n ||
        point_moves > o.max_point_displacement_factor * largest) {
      continue;
    }
    out.push_back({branch, arc, force, (c * force - held).norm()});
  }
  std::stable_sort(out.begin(), out.end(), [](const PullCandidate& a, const PullCandidate& b) {
    return a.static_residual_m < b.static_residual_m;
  });
  return out;
}

}  // namespace

void PullFitOptions::Validate() const {
  const auto check = [](bool ok, const char* field, const std::string& message) {
    CheckOption(ok, kSource, field, message);
  };
  check(rest_s > 0 && std::isfinite(rest_s), "rest_s", "expected seconds > 0");
  check(held_window_s > 0 && std::isfinite(held_window_s), "held_window_s", "expected seconds > 0");
  check(release_margin_s >= 0 && std::isfinite(release_margin_s), "release_margin_s",
        "expected seconds >= 0");
  check(arc_samples >= 1, "arc_samples", "expected at least 1");
  check(max_level >= 0, "max_level", "expected a level >= 0");
  check(min_arc_share >= 0 && min_arc_share < 1, "min_arc_share", "expected a share in [0, 1)");
  check(max_arc_share > min_arc_share && max_arc_share <= 1, "max_arc_share",
        "expected a share in (min_arc_share, 1]");
  check(max_force_n > 0 && std::isfinite(max_force_n), "max_force_n", "expected newtons > 0");
  check(max_point_displacement_factor > 0 && std::isfinite(max_point_displacement_factor),
        "max_point_displacement_factor", "expected a factor > 0");
  check(anchor_distance_m > 0 && std::isfinite(anchor_distance_m), "anchor_distance_m",
        "expected metres > 0");
  check(hold_fraction > 0 && hold_fraction <= 1, "hold_fraction", "expected a share in (0, 1]");
  check(motion_candidates >= 0, "motion_candidates", "expected a count >= 0");
  check(motion.window_s > 0 && std::isfinite(motion.window_s), "motion.window_s",
        "expected seconds > 0");
  check(motion.max_release_shift_s >= 0 && std::isfinite(motion.max_release_shift_s),
        "motion.max_release_shift_s", "expected seconds >= 0");
  check(motion.outlier_factor > 1 && std::isfinite(motion.outlier_factor), "motion.outlier_factor",
        "expected a factor > 1");
  check(motion.outlier_share > 0 && std::isfinite(motion.outlier_share), "motion.outlier_share",
        "expected a share > 0");
}

dynamics::PullSchedule PullFit::Schedule(double anchor_distance_m) const {
  dynamics::PullSchedule s;
  s.rope.branch = branch;
  s.rope.arc_length = arc_length;
  s.rope.anchor = point + anchor_distance_m * force.normalized();
  s.rope.force_n = force.norm();
  s.hold_s = hold_s;
  s.release_s = release_s;
  return s;
}

PullFit FitPull(const Tree& tree, const Trajectories& tracks,
                const Eigen::Isometry3d& world_from_camera, double release_s,
                const std::vector<int>& excluded, const PullFitOptions& options) {
  options.Validate();
  if (tracks.frame_count() < 2) throw InputError("trajectories", "", "expected two frames or more");
  const std::vector<PullObservation> obs =
      Observe(tree, tracks, world_from_camera, release_s, excluded, options);
  if (obs.empty()) {
    throw InputError("trajectories", "",
                     "no marker of the tree has a tracked rest and held position to fit the "
                     "pull to");
  }
  Eigen::VectorXd held(3 * obs.size());
  for (size_t i = 0; i < obs.size(); ++i) held.segment<3>(3 * i) = obs[i].held;
  const double observed = std::sqrt(held.squaredNorm() / obs.size());
  if (!(observed > 1e-4)) {
    throw InputError("trajectories", "",
                     fmt::format("the markers barely moved while held ({:.2f} mm RMS): no pull "
                                 "to fit",
                                 1e3 * observed));
  }
  const std::vector<PullCandidate> ranked = RankCandidates(tree, obs, held, options);
  if (ranked.empty()) {
    throw InputError("simready tree", "",
                     fmt::format("no branch point explains the held displacements with a force "
                                 "of at most {} N moving its point at most {} times the markers' "
                                 "largest displacement",
                                 options.max_force_n, options.max_point_displacement_factor));
  }
  PullFit fit;
  fit.branch = ranked.front().branch;
  fit.arc_length = ranked.front().arc_length;
  fit.force = ranked.front().force;
  fit.residual_rms_m =
      ranked.front().static_residual_m / std::sqrt(static_cast<double>(obs.size()));
  fit.observed_rms_m = observed;
  fit.markers = static_cast<int>(obs.size());
  fit.candidates = static_cast<int>(Candidates(tree, options).size());
  fit.detected_release_s = fit.release_s = release_s;
  fit.hold_s = HoldStart(tracks, obs, world_from_camera, release_s, options.hold_fraction);

  const std::vector<PullCandidate> best(
      ranked.begin(), ranked.begin() + std::min<size_t>(ranked.size(), options.motion_candidates));
  fit.motion = FitPullOnMotion(tree, tracks, world_from_camera, obs, best, fit.hold_s, release_s,
                               options.max_force_n, options.motion);
  if (fit.motion.fitted) {
    fit.branch = fit.motion.candidate.branch;
    fit.arc_length = fit.motion.candidate.arc_length;
    fit.force = fit.motion.candidate.force;
    // Half a step early, so the replay lets go at the step boundary the fit chose.
    fit.release_s = fit.motion.release_s - 0.5 * fit.motion.time_step_s;
    fit.hold_s = std::min(fit.hold_s, fit.release_s);
  }
  fit.point = tree.branches[fit.branch].PointAt(fit.arc_length);
  return fit;
}

}  // namespace simtree::pipeline::detail
