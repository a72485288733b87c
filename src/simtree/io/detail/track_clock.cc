#include "simtree/io/detail/track_clock.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::azure_detail {

void TrackClock::Add(int64_t timestamp_us) {
  if (!times_.empty() && timestamp_us <= times_.back()) {
    throw InputError(source_, fmt::format("{} frame {}", track_, times_.size()),
                     fmt::format("expected a timestamp after the previous frame's {} us, got {} "
                                 "us (timestamps go back)",
                                 times_.back(), timestamp_us));
  }
  times_.push_back(timestamp_us);
}

int64_t TrackClock::MedianPeriodUs() const {
  if (times_.size() < 2) return 0;
  std::vector<int64_t> intervals;
  for (size_t i = 1; i < times_.size(); ++i) intervals.push_back(times_[i] - times_[i - 1]);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return intervals[intervals.size() / 2];
}

int TrackClock::DroppedFrames() const {
  const int64_t period = MedianPeriodUs();
  if (period <= 0) return 0;
  int dropped = 0;
  for (size_t i = 1; i < times_.size(); ++i) {
    const double gap = static_cast<double>(times_[i] - times_[i - 1]) / period;
    if (gap > 1.5) dropped += static_cast<int>(std::lround(gap)) - 1;
  }
  return dropped;
}

}  // namespace simtree::azure_detail
