#pragma once
// The timestamps of one track: each must come after the one before (else InputError naming the
// file, track and frame), and at the end the frame period and how many frames the camera dropped.

#include <cstdint>
#include <string>
#include <vector>

namespace simtree::azure_detail {

class TrackClock {
 public:
  TrackClock(std::string source, std::string track) : source_(source), track_(track) {}
  // Records the next frame's timestamp; throws unless it is later than the previous one.
  void Add(int64_t timestamp_us);
  int frames() const { return static_cast<int>(times_.size()); }
  // The median interval between frames (microseconds), 0 with fewer than two frames.
  int64_t MedianPeriodUs() const;
  // Frames missing from the regular rhythm: over gaps longer than 1.5 periods, round(gap /
  // period) - 1 each.
  int DroppedFrames() const;

 private:
  std::string source_;
  std::string track_;
  std::vector<int64_t> times_;  // 8 bytes a frame: a long recording's worth is small
};

}  // namespace simtree::azure_detail
