#include "simtree/identification/track_outliers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "simtree/core/statistics.h"

namespace simtree {
TrackOutlierReport RemoveTrackOutliers(Trajectories& trajectories,
                                       const TrackOutlierOptions& options) {
  TrackOutlierReport report;
  std::set<int> markers;
  const int n = trajectories.frame_count();
  for (MarkerTrack& track : trajectories.tracks) {
    // Deviation of every valid sample from the per-axis median of its neighbours.
    std::vector<double> deviation(n, -1.0);
    std::vector<double> all;
    for (int i = 0; i < n; ++i) {
      if (!track.valid[i]) continue;
      Eigen::Vector3d median;
      int count = 0;
      for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> around;
        for (int j = std::max(0, i - options.half_window);
             j <= std::min(n - 1, i + options.half_window); ++j) {
          if (j != i && track.valid[j]) around.push_back(track.positions[j][axis]);
        }
        count = static_cast<int>(around.size());
        if (count >= 2) median[axis] = Median(std::move(around));
      }
      if (count < 2) continue;
      deviation[i] = (track.positions[i] - median).norm();
      all.push_back(deviation[i]);
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

}  // namespace simtree
