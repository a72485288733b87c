#pragma once
// Loads the frames of a pull stream ahead of the tracker, a batch at a time on several threads
// (PNG decoding costs more than tracking).

#include <cstddef>
#include <vector>

#include "simtree/io/capture.h"

namespace simtree::tracking::detail {

class FrameLoader {
 public:
  // `threads` 0: every core.
  FrameLoader(const PullStream& stream, int threads);
  // The frame at `index` (frames are asked for in increasing order). Throws what LoadPullFrame
  // throws.
  const RgbdImage& Get(size_t index);

 private:
  const PullStream& stream_;
  int threads_;
  size_t batch_start_ = 0;
  std::vector<RgbdImage> batch_;
};

}  // namespace simtree::tracking::detail
