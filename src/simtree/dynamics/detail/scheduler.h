#pragma once
// Runs per-branch work in the order the model needs, spreading big levels over threads with TBB:
// a level's branches are independent once their parents are done.

#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "simtree/dynamics/detail/branch_model.h"

namespace simtree::dynamics {

class BranchScheduler {
 public:
  // `max_threads`: 0 = every core TBB finds.
  explicit BranchScheduler(int max_threads)
      : max_threads_(max_threads),
        arena_(max_threads > 0 ? std::make_unique<tbb::task_arena>(max_threads)
                               : std::make_unique<tbb::task_arena>()) {}

  // fn(i) for every i in [begin, end), in parallel when the range is big enough.
  template <typename Fn>
  void ForRange(int begin, int end, const Fn& fn) const {
    if (end - begin < kParallelMinBranches || max_threads_ == 1) {
      for (int i = begin; i < end; ++i) fn(i);
      return;
    }
    arena_->execute([&] {
      tbb::parallel_for(tbb::blocked_range<int>(begin, end, kParallelGrain),
                        [&](const tbb::blocked_range<int>& r) {
                          for (int i = r.begin(); i < r.end(); ++i) fn(i);
                        });
    });
  }

  // fn(branch) for every branch, parents before children.
  template <typename Fn>
  void TopDown(const TreeOrder& order, const Fn& fn) const {
    for (size_t l = 0; l + 1 < order.level_begin.size(); ++l) {
      ForRange(order.level_begin[l], order.level_begin[l + 1],
               [&](int i) { fn(order.level_order[i]); });
    }
  }

  // fn(branch) for every branch of every level but the deepest, deepest first: each branch
  // after all of its children.
  template <typename Fn>
  void ParentsBottomUp(const TreeOrder& order, const Fn& fn) const {
    for (size_t l = order.level_begin.size() - 1; l-- > 1;) {
      ForRange(order.level_begin[l - 1], order.level_begin[l],
               [&](int i) { fn(order.level_order[i]); });
    }
  }

 private:
  // Levels with fewer branches than this run on the calling thread: splitting them costs more
  // than it saves.
  static constexpr int kParallelMinBranches = 512;
  static constexpr int kParallelGrain = 64;

  int max_threads_ = 0;
  std::unique_ptr<tbb::task_arena> arena_;
};

}  // namespace simtree::dynamics
