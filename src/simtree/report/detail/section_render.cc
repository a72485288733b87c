// Simulated frames beside the capture's (paper Fig. 15): a few of render/'s side-by-side frames,
// one at the release and the rest spread over the free swing after it.

#include <cmath>

#include <fmt/format.h>

#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"
#include "simtree/report/detail/simulation_info.h"

namespace simtree::report {
namespace {

// Indices of the frames shown: the release and the frames after it, or spread over all.
std::vector<int> PickFrames(int total, int count, double fps, std::optional<double> release_s) {
  if (!release_s || total < 2 || count < 2) return EvenlySpread(total, count);
  const int release = static_cast<int>(std::lround(*release_s * fps));
  if (release < 0 || release >= total - 1) return EvenlySpread(total, count);
  // The release, then count - 1 frames evenly over the rest, the last frame last.
  std::vector<int> picked = {release};
  const double step = (total - 1.0 - release) / (count - 1);
  for (int k = 1; k < count; ++k) {
    const int i = release + static_cast<int>(std::lround(k * step));
    if (i > picked.back()) picked.push_back(i);
  }
  return picked;
}

}  // namespace

Section BuildRenderSection(PageContext& page) {
  Section s{"render", "Simulation beside the capture", "", false, {}};
  const ResultFolder& folder = page.folder();
  const auto frames = folder.Files("render", {".png", ".jpg", ".jpeg"});
  if (frames.empty()) {
    s.Missing("render/ has no frames: the simulation was not rendered beside the capture.");
    return s;
  }
  s.present = true;
  const std::optional<SimulationInfo> sim = ReadSimulationInfo(folder);
  const double fps = sim ? sim->fps : 30.0;
  std::optional<double> release;
  if (sim && sim->pull) release = sim->pull->release_s;
  s.html += fmt::format(
      "<p>Left: the capture's pull-test frames; right: the simulation seen from the pull camera "
      "(paper Fig. 15). {} of {} frames{}.</p>\n",
      std::min<size_t>(frames.size(), page.options().render_frames), frames.size(),
      release ? fmt::format(", from the release at {:.2f} s", *release) : "");
  std::string figures;
  for (int i :
       PickFrames(static_cast<int>(frames.size()), page.options().render_frames, fps, release)) {
    figures += page.Figure(
        frames[i], fmt::format("{}: t = {:.2f} s", frames[i].filename().string(), i / fps), s);
  }
  s.html += "<div class=\"frames\">\n" + figures + "</div>\n";
  if (!sim) s.Remark("Frame times assume 30 fps (simulate/simulation.json is missing).");
  return s;
}

}  // namespace simtree::report
