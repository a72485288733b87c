#pragma once
// The tracker's inputs checked before any frame is tracked: the pull stream folder, the init
// against markers.json and frames.csv, and the first frame's tape colour.

#include <filesystem>
#include <vector>

#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"
#include "simtree/tracking/detail/color_model.h"

namespace simtree::tracking::detail {

// Reads pull_dir's intrinsics.json, frames.csv and markers.json (when present) and checks that
// every frame file exists. Throws InputError naming the file otherwise.
PullStream OpenPullStream(const std::filesystem::path& pull_dir);

// The index in stream.frames of init.frame; throws InputError when an init marker is not in
// markers.json (when the stream has one), or the frame is not in frames.csv, or a pixel lies
// outside the image.
size_t CheckInit(const PullStream& stream, const TrackInit& init,
                 const std::filesystem::path& init_source);

// The colour model for `color` (--color) fitted to the tape around the init pixels of `first`.
// Throws InputError when no init pixel shows the colour at all (a wrong --color or init).
TapeColorModel ChooseColorModel(const std::string& color, const RgbImage& first,
                                const TrackInit& init, const std::string& first_source);

}  // namespace simtree::tracking::detail
