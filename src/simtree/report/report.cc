#include "simtree/report/report.h"

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/javascript_libraries.h"
#include "simtree/report/detail/page_builder.h"
#include "simtree/report/detail/page_context.h"
#include "simtree/report/detail/result_folder.h"
#include "simtree/report/detail/sections.h"

#ifndef SIMTREE_JAVASCRIPT_DIR
#define SIMTREE_JAVASCRIPT_DIR "/usr/share/javascript"
#endif

namespace simtree::report {
namespace {

// Room kept for what the page adds around the animation's arrays (its JSON keys, the viewer).
constexpr int64_t kPageMargin = 64 * 1024;

// "result" for "out/result", "out/result/" and "out/result/." alike.
std::string FolderName(const std::filesystem::path& dir) {
  std::filesystem::path p = std::filesystem::absolute(dir).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().empty() ? p.string() : p.filename().string();
}

std::string Subtitle(const ResultFolder& folder) {
  std::string out =
      "Result folder " + std::filesystem::absolute(folder.root).lexically_normal().string();
  if (folder.run) {
    if (!folder.run->capture.empty()) out += "; capture " + folder.run->capture;
    if (!folder.run->simtree_version.empty()) out += "; simtree " + folder.run->simtree_version;
  }
  return out;
}

std::string Footer(const ReportResult& r) {
  return fmt::format(
      "simtree report: images {}, JavaScript libraries {} (three.js r111 and OrbitControls from "
      "libjs-three, Chart.js from libjs-chart.js, inlined), animation data {}. No network is used.",
      FormatBytes(r.image_bytes), FormatBytes(r.library_bytes), FormatBytes(r.animation.bytes));
}

}  // namespace

std::filesystem::path DefaultJavaScriptDir() { return SIMTREE_JAVASCRIPT_DIR; }

void ReportOptions::Validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw Error("report options: " + what);
  };
  require(max_bytes >= 2'000'000,
          fmt::format("max_bytes must be at least 2 MB, got {}", max_bytes));
  require(animation_max_bytes >= 0, "animation_max_bytes must not be negative");
  require(image_max_bytes >= 0, "image_max_bytes must not be negative");
  require(min_animation_fps > 0 && min_animation_fps <= 240,
          fmt::format("min_animation_fps must be in (0, 240], got {}", min_animation_fps));
  require(overlay_frames >= 0 && overlay_frames <= 100, "overlay_frames must be in [0, 100]");
  require(render_frames >= 0 && render_frames <= 100, "render_frames must be in [0, 100]");
  require(max_image_width >= 64 && max_image_width <= 8192,
          "max_image_width must be in [64, 8192]");
  require(max_branch_rows >= 0, "max_branch_rows must not be negative");
  require(max_chart_samples >= 16, "max_chart_samples must be at least 16");
}

const SectionReport* ReportResult::Find(const std::string& id) const {
  for (const SectionReport& s : sections) {
    if (s.id == id) return &s;
  }
  return nullptr;
}

std::string BuildReportHtml(const std::filesystem::path& result_dir, const ReportOptions& options,
                            ReportResult* result) {
  options.Validate();
  const ResultFolder folder = OpenResultFolder(result_dir);
  const JavaScriptLibraries libraries = LoadJavaScriptLibraries(
      options.javascript_dir.empty() ? DefaultJavaScriptDir() : options.javascript_dir);
  if (!libraries.complete() && !options.allow_missing_javascript) {
    std::string missing = libraries.missing;
    while (!missing.empty() && missing.back() == '\n') missing.pop_back();
    throw Error("report: " + missing);
  }
  ReportResult out;
  PageContext page(folder, options, libraries.complete());
  PageParts parts;
  parts.title = options.title.empty() ? "simtree report: " + FolderName(result_dir) : options.title;
  parts.subtitle = Subtitle(folder);
  parts.libraries = &libraries;
  for (auto build :
       {BuildStagesSection, BuildViewsSection, BuildRegistrationSection, BuildReconstructionSection,
        BuildTrackingSection, BuildIdentificationSection, BuildBranchesSection, BuildRenderSection,
        BuildPaperTablesSection, BuildEvalSection}) {
    parts.sections.push_back(build(page));
  }
  // The animation gets what the rest of the page leaves; it is shown second, after the stages.
  parts.data = page.data();
  const int64_t rest = static_cast<int64_t>(AssemblePage(parts).size()) + kPageMargin;
  const int64_t budget = std::min(options.animation_max_bytes, options.max_bytes - rest);
  parts.sections.insert(parts.sections.begin() + 1,
                        BuildAnimationSection(page, budget, &out.animation));
  parts.data = page.data();
  out.image_bytes = page.image_bytes();
  out.library_bytes = libraries.complete() ? libraries.bytes() : 0;
  parts.footer = Footer(out);
  std::string html = AssemblePage(parts);
  if (static_cast<int64_t>(html.size()) > options.max_bytes) {
    throw Error(fmt::format("report: the page would be {} bytes, over the limit of {}", html.size(),
                            options.max_bytes));
  }
  out.bytes = static_cast<int64_t>(html.size());
  for (const Section& s : parts.sections) {
    out.sections.push_back({s.id, s.title, s.present, s.notes});
    for (const std::string& n : s.notes) out.notes.push_back(s.title + ": " + n);
  }
  if (result) *result = std::move(out);
  return html;
}

ReportResult WriteReport(const std::filesystem::path& result_dir, const ReportOptions& options) {
  ReportResult result;
  const std::string html = BuildReportHtml(result_dir, options, &result);
  result.path = options.output.empty() ? result_dir / "report.html" : options.output;
  WriteFileAtomically(result.path, html);
  return result;
}

}  // namespace simtree::report
