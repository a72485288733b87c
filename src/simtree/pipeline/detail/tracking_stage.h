#pragma once
// The track stage on the pull stream itself (the tracking library), as opposed to trajectories
// given with RunOptions::tracks.

#include <string>

#include "simtree/pipeline/stage.h"

namespace simtree::pipeline::detail {

// Whether this build can track the pull stream (the tracking library's Track is linked).
bool TrackingBuilt();

// Tracks capture/pull/ from pull/init.json into out_dir (trajectories.csv, boxes.csv, overlay
// frames); returns the summary. Throws NotBuiltError when tracking is not built.
std::string TrackPullStream(const StageContext& context);

}  // namespace simtree::pipeline::detail
