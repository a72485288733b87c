#include "simtree/tracking/detail/frame_loader.h"

#include <algorithm>
#include <exception>
#include <mutex>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace simtree::tracking::detail {

FrameLoader::FrameLoader(const PullStream& stream, int threads)
    : stream_(stream), threads_(threads > 0 ? threads : tbb::this_task_arena::max_concurrency()) {}

const RgbdImage& FrameLoader::Get(size_t index) {
  if (index >= batch_start_ && index < batch_start_ + batch_.size()) {
    return batch_[index - batch_start_];
  }
  const size_t count =
      std::min<size_t>(4 * static_cast<size_t>(threads_), stream_.frames.size() - index);
  batch_.assign(count, RgbdImage{});
  batch_start_ = index;
  std::exception_ptr error;
  std::mutex mutex;
  tbb::task_arena arena(threads_);
  arena.execute([&] {
    tbb::parallel_for(size_t{0}, count, [&](size_t k) {
      try {
        batch_[k] = LoadPullFrame(stream_, index + k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!error) error = std::current_exception();
      }
    });
  });
  if (error) {
    // Report the first bad frame in stream order: load them one by one up to it.
    for (size_t k = 0; k < count; ++k) batch_[k] = LoadPullFrame(stream_, index + k);
  }
  return batch_[0];
}

}  // namespace simtree::tracking::detail
