#include "simtree/pipeline/detail/tracking_stage.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/io/track_init.h"
#include "simtree/tracking/track.h"

namespace simtree::pipeline::detail {

bool TrackingBuilt() { return true; }

std::string TrackPullStream(const StageContext& context) {
  const std::filesystem::path pull = context.capture_dir / "pull";
  const TrackInit init = ReadTrackInitJson(pull / "init.json");
  const tracking::TrackOptions options;
  const tracking::TrackResult result = tracking::Track(pull, init, options);
  tracking::TrackOutputOptions outputs;
  outputs.overlay = true;
  tracking::WriteTrackOutputs(result, context.out_dir, outputs);
  for (const std::string& warning : result.warnings) spdlog::warn("track: {}", warning);
  int64_t tracked = 0, samples = 0;
  for (const tracking::MarkerCounts& c : result.counts) {
    tracked += c.tracked;
    samples += c.tracked + c.predicted + c.lost;
  }
  return fmt::format(
      "{} markers over {} frames, {:.0f}% of marker-frames measured{}",
      result.trajectories.marker_count(), result.trajectories.frame_count(),
      samples > 0 ? 100.0 * tracked / samples : 0.0,
      result.never_found.empty() ? "" : fmt::format(", {} never found", result.never_found.size()));
}

}  // namespace simtree::pipeline::detail
