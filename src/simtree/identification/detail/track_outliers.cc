#include "simtree/identification/detail/track_outliers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Cholesky>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"

namespace simtree::identification {
namespace {

constexpr int kCoefficients = 4;  // a cubic in time
using Basis = Eigen::Matrix<double, kCoefficients, 1>;

// How far sample `i` lies from the smooth motion around it: a cubic in time is fitted to the valid
// samples within `half_window` frames (i included) by least trimmed squares, leaving out the
// `max_trimmed` samples whose removal fits the rest best (every choice tried: a window has at most
// 2 half_window + 1 samples). A jump of a frame or two therefore falls out of its own and its
// neighbours' fits, and only the jumped samples lie far from the curve. A cubic over +-4 frames
// follows a 2 Hz swing to well under a millimetre, where a median of the neighbours would sit
// centimetres inside each turning point. Returns a negative value when too few samples lie
// around i, or none on one side, to judge it.
double DeviationFromLocalCubic(const MarkerTrack& track, int i,
                               const TrackOutlierOptions& options) {
  const int n = static_cast<int>(track.positions.size());
  std::vector<Basis> rows;
  std::vector<Eigen::Vector3d> values;
  bool before = false;
  bool after = false;
  for (int j = std::max(0, i - options.half_window); j <= std::min(n - 1, i + options.half_window);
       ++j) {
    if (!track.valid[j]) continue;
    const double s = static_cast<double>(j - i) / options.half_window;  // in [-1, 1]
    rows.push_back(Basis(1.0, s, s * s, s * s * s));
    values.push_back(track.positions[j]);
    before |= j < i;
    after |= j > i;
  }
  const int m = static_cast<int>(rows.size());
  // Two samples beyond the coefficients keep a residual to judge the fit by.
  const int trimmed = std::min(options.max_trimmed, m - kCoefficients - 2);
  if (trimmed < 0 || !before || !after) return -1.0;

  // Normal equations of the whole window; each trial takes the left-out rows off them.
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Matrix<double, kCoefficients, 3> moment = Eigen::Matrix<double, kCoefficients, 3>::Zero();
  double sum_squares = 0.0;
  for (int k = 0; k < m; ++k) {
    normal += rows[k] * rows[k].transpose();
    moment += rows[k] * values[k].transpose();
    sum_squares += values[k].squaredNorm();
  }
  double best_residual = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_at_i = Eigen::Vector3d::Zero();
  auto try_without = [&](int a, int b) {  // -1: nobody left out
    Eigen::Matrix4d n_kept = normal;
    Eigen::Matrix<double, kCoefficients, 3> m_kept = moment;
    double ss_kept = sum_squares;
    for (int k : {a, b}) {
      if (k < 0) continue;
      n_kept -= rows[k] * rows[k].transpose();
      m_kept -= rows[k] * values[k].transpose();
      ss_kept -= values[k].squaredNorm();
    }
    const Eigen::LDLT<Eigen::Matrix4d> solver(n_kept);
    if (solver.info() != Eigen::Success) return;
    const Eigen::Matrix<double, kCoefficients, 3> coefficients = solver.solve(m_kept);
    // Sum of squared residuals of the kept samples: |X|^2 - tr(C^T A^T X).
    const double residual = ss_kept - (coefficients.cwiseProduct(m_kept)).sum();
    if (residual < best_residual) {
      best_residual = residual;
      best_at_i = coefficients.row(0).transpose();  // the curve at s = 0
    }
  };
  if (trimmed == 0) try_without(-1, -1);
  for (int a = 0; a < m && trimmed >= 1; ++a) {
    if (trimmed == 1) {
      try_without(a, -1);
      continue;
    }
    for (int b = a + 1; b < m; ++b) try_without(a, b);
  }
  if (!std::isfinite(best_residual)) return -1.0;
  return (track.positions[i] - best_at_i).norm();
}

}  // namespace

void TrackOutlierOptions::Validate() const {
  CheckAtLeast("half_window", half_window, 3);
  CheckThat(max_trimmed >= 0 && max_trimmed <= 2, "max_trimmed", "0, 1 or 2", max_trimmed);
  CheckPositive("threshold", threshold);
  CheckNonNegative("min_deviation_m", min_deviation_m);
}

TrackOutlierReport RemoveTrackOutliers(Trajectories& trajectories,
                                       const TrackOutlierOptions& options) {
  options.Validate();
  TrackOutlierReport report;
  std::set<int> markers;
  const int n = trajectories.frame_count();
  for (MarkerTrack& track : trajectories.tracks) {
    std::vector<double> deviation(n, -1.0);
    std::vector<double> all;
    for (int i = 0; i < n; ++i) {
      if (!track.valid[i]) continue;
      deviation[i] = DeviationFromLocalCubic(track, i, options);
      if (deviation[i] >= 0.0) all.push_back(deviation[i]);
    }
    if (all.size() < 5) continue;
    // A robust scale of the ordinary deviations (noise and the smooth motion's small residue).
    const double scale = 1.4826 * Median(std::move(all));
    const double limit = std::max(options.threshold * scale, options.min_deviation_m);
    for (int i = 0; i < n; ++i) {
      if (deviation[i] > limit) {
        track.valid[i] = false;
        track.positions[i].setConstant(std::numeric_limits<double>::quiet_NaN());
        report.samples.emplace_back(track.marker, i);
        markers.insert(track.marker);
      }
    }
  }
  report.removed = static_cast<int>(report.samples.size());
  if (report.removed > 0) {
    std::string list;
    for (int m : markers) list += (list.empty() ? "" : ", ") + std::to_string(m);
    report.note = fmt::format("removed {} tracker jump{} (marker{} {})", report.removed,
                              report.removed == 1 ? "" : "s", markers.size() == 1 ? "" : "s", list);
  }
  return report;
}

}  // namespace simtree::identification
