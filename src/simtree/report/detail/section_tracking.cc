// Tracking: a few overlay frames of the tracker, and the marker trajectories as an interactive
// chart (each marker's motion from its first position, in the pull camera's frame).

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/trajectories.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

double Round(double v, double unit) { return std::round(v / unit) * unit; }

nlohmann::json TrajectoriesJson(const Trajectories& t, int max_samples) {
  const int step = std::max(1, (t.frame_count() + max_samples - 1) / std::max(max_samples, 1));
  nlohmann::json times = nlohmann::json::array();
  for (int f = 0; f < t.frame_count(); f += step) times.push_back(Round(t.times_s[f], 1e-4));
  nlohmann::json markers = nlohmann::json::array();
  for (const MarkerTrack& track : t.tracks) {
    int first = 0;
    while (first < t.frame_count() && !track.valid[first]) ++first;
    nlohmann::json axes[3] = {nlohmann::json::array(), nlohmann::json::array(),
                              nlohmann::json::array()};
    for (int f = 0; f < t.frame_count(); f += step) {
      for (int a = 0; a < 3; ++a) {
        if (first < t.frame_count() && track.valid[f]) {
          axes[a].push_back(
              Round(1000 * (track.positions[f][a] - track.positions[first][a]), 0.01));
        } else {
          axes[a].push_back(nullptr);
        }
      }
    }
    markers.push_back({{"id", track.marker},
                       {"label", fmt::format("M{}", track.marker)},
                       {"x", std::move(axes[0])},
                       {"y", std::move(axes[1])},
                       {"z", std::move(axes[2])}});
  }
  return {{"times", std::move(times)}, {"markers", std::move(markers)}};
}

void AddOverlays(PageContext& page, Section& s) {
  const ResultFolder& folder = page.folder();
  const auto frames = folder.Files("track/overlay", {".png", ".jpg", ".jpeg"});
  if (frames.empty()) {
    s.Missing("track/overlay/ has no frames: no tracking overlay to show.");
    return;
  }
  std::string figures;
  for (int i : EvenlySpread(static_cast<int>(frames.size()), page.options().overlay_frames)) {
    figures += page.Figure(frames[i], frames[i].filename().string(), s,
                           std::min(page.options().max_image_width, 480));
  }
  s.html += "<div class=\"gallery\">\n" + figures + "</div>\n";
  s.Remark(fmt::format("{} of the {} overlay frames in track/overlay/.",
                       std::min<size_t>(frames.size(), page.options().overlay_frames),
                       frames.size()));
}

void AddTrajectories(PageContext& page, Section& s) {
  const std::filesystem::path file = page.folder().TrajectoriesFile();
  if (file.empty()) {
    s.Missing(
        "No marker trajectories: track/trajectories.csv is missing (and materials.json names "
        "none that is reachable).");
    return;
  }
  Trajectories t;
  try {
    t = ReadTrajectoriesCsv(file);
  } catch (const Error& e) {
    s.LeftOut(std::string("The trajectories could not be read: ") + e.what());
    return;
  }
  s.present = true;
  page.SetData("trajectories", TrajectoriesJson(t, page.options().max_chart_samples));
  s.html += fmt::format(
      "<h3>Marker trajectories</h3>\n<p>{} markers over {} frames ({:.2f} s) from {}: each "
      "marker's motion from its first position (mm), in the pull camera's frame (x right, y down, "
      "z away from the camera).</p>\n",
      t.marker_count(), t.frame_count(),
      t.frame_count() > 0 ? t.times_s.back() - t.times_s[0] : 0.0,
      EscapeHtml(RelativeName(page.folder(), file)));
  if (!page.scripts()) {
    s.LeftOut("The trajectory chart needs the JavaScript libraries, which are not in this page.");
    return;
  }
  s.html +=
      "<div class=\"chart-controls\"><label>marker <select id=\"trajectory-marker\"></select>"
      "</label></div>\n<div class=\"chart-box wide\"><canvas id=\"chart-trajectories\"></canvas>"
      "</div>\n";
}

}  // namespace

Section BuildTrackingSection(PageContext& page) {
  Section s{"tracking", "Tracking", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFolder("track")) {
    s.Missing("track/ is not in the result: the markers were not tracked here.");
  } else {
    s.present = true;
    AddOverlays(page, s);
    if (folder.HasFile("track/boxes.csv")) {
      const std::string text = ReadFile(folder.Path("track/boxes.csv"));
      const auto lines = std::count(text.begin(), text.end(), '\n');
      s.Remark(fmt::format("track/boxes.csv: {} lines of marker boxes.", lines));
    } else {
      s.Missing("track/boxes.csv is missing.");
    }
  }
  AddTrajectories(page, s);
  return s;
}

}  // namespace simtree::report
