// The stages' table from run.json, or what the folders hold when there is no run.json.

#include <cmath>

#include <fmt/format.h>

#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

// The status with its colour; `text` replaces the word shown when given.
std::string StatusCell(const std::string& status, const std::string& text = "") {
  std::string css = "status-other";
  if (status == "done") css = "status-done";
  if (status == "failed") css = "status-failed";
  if (status == "skipped" || status == "not run") css = "status-skipped";
  return fmt::format("<span class=\"{}\">{}</span>", css, EscapeHtml(text.empty() ? status : text));
}

}  // namespace

Section BuildStagesSection(PageContext& page) {
  const ResultFolder& folder = page.folder();
  Section s{"stages", "Stages", "", false, {}};
  if (!folder.run_problem.empty()) {
    s.LeftOut("run.json could not be read: " + folder.run_problem);
  }
  if (folder.run) {
    s.present = true;
    const RunManifest& run = *folder.run;
    HtmlTable info({"", ""}, "facts");
    info.AddRow({"simtree", run.simtree_version.empty() ? "?" : run.simtree_version});
    info.AddRow({"capture", run.capture.empty() ? "?" : run.capture});
    s.html += info.Html();
    HtmlTable table({"stage", "status", "wall time (s)", "summary", "outputs"}, "stages");
    double total = 0;
    for (const StageRecord& r : run.stages) {
      if (std::isfinite(r.wall_s)) total += r.wall_s;
      std::string outputs;
      for (const std::string& o : r.outputs) outputs += (outputs.empty() ? "" : ", ") + o;
      table.AddHtmlRow({EscapeHtml(r.name), StatusCell(r.status),
                        EscapeHtml(FormatNumber(r.wall_s, 1)), EscapeHtml(r.summary),
                        "<span class=\"small\">" + EscapeHtml(outputs) + "</span>"});
    }
    s.html += table.Html();
    s.Remark(fmt::format("{} stages, {:.1f} s in all.", run.stages.size(), total));
    return s;
  }
  if (folder.run_problem.empty()) {
    s.Missing("run.json is not in this result folder: the table lists the stage folders found.");
  }
  HtmlTable table({"stage", "folder"}, "stages");
  for (const char* name : kStageNames) {
    const bool here = folder.HasFolder(name);
    s.present = s.present || here;
    table.AddHtmlRow({EscapeHtml(name),
                      here ? StatusCell("done", "present") : StatusCell("not run", "missing")});
  }
  s.html += table.Html();
  return s;
}

}  // namespace simtree::report
