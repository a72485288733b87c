#pragma once
// Groups decoded frames into captures by timestamp, in the order the recording holds them: a
// frame joins the open capture when its track is not in it yet and its time (depth and IR moved
// back by the recording's depth delay) is within the tolerance of the capture's; otherwise the
// open capture is closed and handed out, and the frame opens the next one. At most one capture is
// held.

#include <cstdint>
#include <optional>

#include "simtree/io/azure_kinect.h"

namespace simtree::azure_detail {

class CapturePairer {
 public:
  CapturePairer(int64_t tolerance_us, int64_t depth_delay_us)
      : tolerance_us_(tolerance_us), depth_delay_us_(depth_delay_us) {}

  // Each returns the capture the frame closed, if it closed one.
  std::optional<AzureCapture> AddColor(int64_t timestamp_us, RgbImage image);
  std::optional<AzureCapture> AddDepth(int64_t timestamp_us, DepthImage image);
  std::optional<AzureCapture> AddIr(int64_t timestamp_us, DepthImage image);
  // The open capture, at the end of the recording.
  std::optional<AzureCapture> Flush();

 private:
  // Closes the open capture unless a frame at `aligned_us` whose track it already holds
  // (`taken`) may join it; opens a new one when needed.
  std::optional<AzureCapture> Admit(int64_t aligned_us, bool taken);

  int64_t tolerance_us_;
  int64_t depth_delay_us_;
  std::optional<AzureCapture> open_;
  int64_t open_time_us_ = 0;
  int next_index_ = 0;
};

}  // namespace simtree::azure_detail
