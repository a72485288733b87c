// The simulated pull-and-release in a 3D view: simulate/nodes.bin replayed in the page (three.js,
// orbit controls, play/pause, a time slider), with the rest radii, levels and material sources of
// the tree that was simulated when its nodes match.

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_file.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/report/detail/animation.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"
#include "simtree/report/detail/simulation_info.h"

namespace simtree::report {
namespace {

namespace fs = std::filesystem;

// The simulated tree: build/simready.json, else the file simulation.json names.
std::optional<Tree> FindTree(const ResultFolder& folder, const std::optional<SimulationInfo>& sim) {
  std::vector<fs::path> candidates = {folder.Path("build/simready.json")};
  if (sim && !sim->tree.empty()) {
    const fs::path p = sim->tree;
    candidates.insert(candidates.end(), {p, folder.root / p, folder.root.parent_path() / p});
  }
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(c, ec)) continue;
    try {
      return ReadTreeFile(c);
    } catch (const Error&) {
    }
  }
  return std::nullopt;
}

double Extent(const std::vector<float>& xyz, size_t count) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e30), hi = -lo;
  for (size_t i = 0; i + 2 < count; i += 3) {
    const Eigen::Vector3d p(xyz[i], xyz[i + 1], xyz[i + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return count >= 3 ? (hi - lo).norm() : 0.0;
}

// Radii, levels and sources from `tree` when its branches have the frames' node counts.
AnimationDecor DecorFrom(const dynamics::NodeFrames& frames, const std::optional<Tree>& tree,
                         Section& s) {
  AnimationDecor decor;
  bool matches = tree && tree->size() == static_cast<int>(frames.branch_node_count.size());
  for (int b = 0; matches && b < tree->size(); ++b) {
    matches = tree->branches[b].nodes.size() == frames.branch_node_count[b];
  }
  if (!matches) {
    s.LeftOut(
        "No tree file matches nodes.bin (build/simready.json or simulation.json's tree): "
        "branches are drawn at one radius.");
    return decor;
  }
  std::vector<float> rest;
  for (const Branch& b : tree->branches) {
    decor.branch_level.push_back(b.level);
    decor.branch_source.push_back(b.material ? ToString(b.material->source) : "");
    for (const Node& n : b.nodes) {
      decor.radii.push_back(static_cast<float>(n.radius));
      for (int a = 0; a < 3; ++a) rest.push_back(static_cast<float>(n.position[a]));
    }
  }
  // A tree read at another scale than it was simulated at (the authors' .txt): scale the radii.
  const double tree_extent = Extent(rest, rest.size());
  const double frame_extent = Extent(frames.xyz, static_cast<size_t>(frames.node_count) * 3);
  if (tree_extent > 0 && std::abs(frame_extent / tree_extent - 1) > 0.01) {
    for (float& r : decor.radii) r = static_cast<float>(r * frame_extent / tree_extent);
  }
  return decor;
}

std::optional<AnimationDecor::Rope> RopeOf(const dynamics::NodeFrames& frames,
                                           const std::optional<SimulationInfo>& sim) {
  if (!sim || !sim->pull) return std::nullopt;
  int best = 0;
  double best_d = 1e30;
  for (int n = 0; n < frames.node_count; ++n) {
    const Eigen::Vector3d p(frames.xyz[3 * n], frames.xyz[3 * n + 1], frames.xyz[3 * n + 2]);
    const double d = (p - sim->pull->point).squaredNorm();
    if (d < best_d) best_d = d, best = n;
  }
  return AnimationDecor::Rope{best, sim->pull->anchor, sim->pull->hold_s, sim->pull->release_s};
}

std::string NodesSent(int stride) {
  if (stride <= 1) return "every node";
  return fmt::format(
      "one node in {} of each branch and its tip; the page moves the others with "
      "their neighbours",
      stride);
}

std::string Facts(const AnimationReport& a, const std::optional<SimulationInfo>& sim) {
  HtmlTable table({"", ""}, "facts");
  table.AddRow({"simulated", fmt::format("{} nodes, {} frames at {:.0f} fps ({:.2f} s)", a.nodes,
                                         a.frames, a.fps, (a.frames - 1) / a.fps)});
  table.AddRow(
      {"in this page",
       fmt::format("{} nodes ({}), {} frames at {:.1f} fps, 16-bit positions ({:.0f} \xC2\xB5m "
                   "steps): {}",
                   a.sent_nodes, NodesSent(a.node_stride), a.sent_frames, a.sent_fps,
                   1e6 * a.quantisation_step_m, FormatBytes(a.bytes))});
  if (sim && sim->pull) {
    table.AddRow(
        {"pull", fmt::format("branch {}, {:.0f} N, held from {:.2f} s, released at {:.2f} s",
                             sim->pull->branch, sim->pull->tension_n, sim->pull->hold_s,
                             sim->pull->release_s)});
  }
  if (sim && !sim->integrator.empty()) table.AddRow({"integrator", sim->integrator});
  return table.Html();
}

constexpr const char* kViewerHtml = R"HTML(<div class="viewer">
<div id="viewer-canvas" class="viewer-canvas"></div>
<div class="viewer-controls">
<button id="viewer-play" type="button">Pause</button>
<input id="viewer-time" type="range" min="0" max="1" step="0.001" value="0">
<span id="viewer-clock">0.00 s</span>
<label>speed <select id="viewer-speed"><option value="0.25">0.25x</option><option value="0.5">0.5x</option><option value="1" selected>1x</option><option value="2">2x</option></select></label>
<label>colour <select id="viewer-colour"><option value="bark">bark</option><option value="level">level</option><option value="source">source</option></select></label>
</div>
<p class="note">Drag to orbit, scroll to zoom, right-drag to pan. The rope (red) pulls until its release. Colour by source: measured green, interpolated amber, default grey.</p>
<pre id="viewer-probe" class="probe"></pre>
</div>
)HTML";

}  // namespace

Section BuildAnimationSection(PageContext& page, int64_t budget_bytes, AnimationReport* report) {
  Section s{"animation", "Pull and release (3D)", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFile("simulate/nodes.bin")) {
    s.Missing(
        "simulate/nodes.bin is not in the result: nothing was simulated (or it was run "
        "with --no-nodes).");
    return s;
  }
  dynamics::NodeFrames frames;
  try {
    frames = dynamics::ReadNodeFrames(folder.Path("simulate/nodes.bin"));
  } catch (const Error& e) {
    s.LeftOut(std::string("simulate/nodes.bin could not be read: ") + e.what());
    return s;
  }
  s.present = true;
  if (!page.scripts()) {
    s.LeftOut(
        fmt::format("The 3D view needs the JavaScript libraries, which are not in this "
                    "page ({} nodes, {} frames simulated).",
                    frames.node_count, frames.frame_count));
    return s;
  }
  const std::optional<SimulationInfo> sim = ReadSimulationInfo(folder);
  const AnimationPlan plan = PlanAnimation(frames, budget_bytes, page.options().min_animation_fps);
  if (!plan.fits) {
    s.LeftOut(fmt::format("The animation ({} nodes, {} frames) does not fit the {} left for it.",
                          frames.node_count, frames.frame_count, FormatBytes(budget_bytes)));
    return s;
  }
  AnimationDecor decor = DecorFrom(frames, FindTree(folder, sim), s);
  decor.rope = RopeOf(frames, sim);
  AnimationReport local;
  AnimationReport& a = report ? *report : local;
  page.SetData("animation", AnimationPayload(frames, plan, decor, &a));
  s.html += kViewerHtml;
  if (a.sent_fps < a.fps || a.node_stride > 1) {
    s.notes.push_back(
        fmt::format("The animation is sent at {:.1f} of {:.0f} fps with {} to fit its budget.",
                    a.sent_fps, a.fps, NodesSent(a.node_stride)));
  }
  s.html += Facts(a, sim);
  return s;
}

}  // namespace simtree::report
