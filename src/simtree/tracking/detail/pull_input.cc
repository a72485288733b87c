#include "simtree/tracking/detail/pull_input.h"

#include <algorithm>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree::tracking::detail {

PullStream OpenPullStream(const fs::path& pull_dir) {
  if (!fs::is_directory(pull_dir)) {
    throw InputError(pull_dir.string(), "",
                     "expected a pull-test stream folder (a capture's pull/), no such folder");
  }
  PullStream pull;
  pull.directory = pull_dir;
  pull.intrinsics = ReadIntrinsicsJson(pull_dir / "intrinsics.json");
  pull.frames = ReadFramesCsv(pull_dir / "frames.csv");
  if (pull.frames.empty()) {
    throw InputError((pull_dir / "frames.csv").string(), "", "expected at least one frame");
  }
  for (const PullFrame& f : pull.frames) {
    for (const std::string& name : {f.color, f.depth}) {
      if (!fs::exists(pull_dir / name)) {
        throw InputError((pull_dir / name).string(), fmt::format("frame {}", f.frame),
                         "expected the image frames.csv names, no such file");
      }
    }
  }
  if (fs::exists(pull_dir / "markers.json")) {
    pull.markers = ReadMarkersJson(pull_dir / "markers.json");
    pull.has_markers = true;
  }
  return pull;
}

size_t CheckInit(const PullStream& stream, const TrackInit& init, const fs::path& init_source) {
  const std::string source = init_source.string();
  if (init.markers.empty()) throw InputError(source, "markers", "expected at least one marker");
  for (size_t i = 0; i < init.markers.size(); ++i) {
    const MarkerPixel& m = init.markers[i];
    const std::string where = fmt::format("markers[{}] (id {})", i, m.id);
    if (stream.has_markers && std::none_of(stream.markers.begin(), stream.markers.end(),
                                           [&](const MarkerLink& l) { return l.id == m.id; })) {
      throw InputError(source, where,
                       fmt::format("marker {} is not in {}", m.id,
                                   (stream.directory / "markers.json").string()));
    }
    if (!stream.intrinsics.Contains(m.pixel.x(), m.pixel.y())) {
      throw InputError(source, where,
                       fmt::format("pixel ({:.1f}, {:.1f}) is outside the {}x{} image", m.pixel.x(),
                                   m.pixel.y(), stream.intrinsics.width, stream.intrinsics.height));
    }
  }
  const auto it = std::find_if(stream.frames.begin(), stream.frames.end(),
                               [&](const PullFrame& f) { return f.frame == init.frame; });
  if (it == stream.frames.end()) {
    throw InputError(source, "frame",
                     fmt::format("frame {} is not in {}", init.frame,
                                 (stream.directory / "frames.csv").string()));
  }
  return static_cast<size_t>(it - stream.frames.begin());
}

TapeColorModel ChooseColorModel(const std::string& color, const RgbImage& first,
                                const TrackInit& init, const std::string& first_source) {
  const TapeColorModel prior = ColorModelFromName(color);
  std::vector<Eigen::Vector2d> pixels;
  for (const MarkerPixel& m : init.markers) pixels.push_back(m.pixel);
  const int radius = std::max(3, first.width / 160);
  int found = 0;
  const TapeColorModel fitted = FitColorModel(prior, first, pixels, radius, 12, &found);
  if (found == 0) {
    throw InputError(first_source, "",
                     fmt::format("no pixel within {} px of any init marker has the tape colour "
                                 "({}): check --color and the init pixels",
                                 radius, prior.Describe()));
  }
  return fitted;
}

}  // namespace simtree::tracking::detail
