#include "simtree/pipeline/detail/tracking_stage.h"

#include "simtree/core/error.h"

namespace simtree::pipeline::detail {

bool TrackingBuilt() { return false; }

std::string TrackPullStream(const StageContext& context) {
  throw NotBuiltError(
      "track: tracking the pull stream is not built in this version; give the trajectories "
      "with --tracks FILE");
}

}  // namespace simtree::pipeline::detail
