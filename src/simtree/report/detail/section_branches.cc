// The simulation-ready tree (build/simready.json): its numbers and a row per branch with the
// geometry, the three modes' frequencies and damping ratios and where they came from.

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/tree_summary.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"
#include "simtree/report/detail/tree_facts.h"

namespace simtree::report {
namespace {

std::vector<std::string> BranchRow(const Branch& b) {
  std::vector<std::string> row = {std::to_string(b.id), std::to_string(b.parent),
                                  std::to_string(b.level), EscapeHtml(FormatNumber(b.Length(), 3)),
                                  EscapeHtml(FormatNumber(1000 * b.base().radius, 1))};
  if (!b.material) {
    for (int i = 0; i < 7; ++i) row.push_back("");
    row.push_back("<span class=\"source-none\">none</span>");
    return row;
  }
  const Material& m = *b.material;
  for (const Mode& mode : m.modes) row.push_back(EscapeHtml(FormatNumber(mode.frequency_hz, 3)));
  for (const Mode& mode : m.modes) row.push_back(EscapeHtml(FormatNumber(mode.damping_ratio, 4)));
  row.push_back(EscapeHtml(FormatNumber(m.stiffness, m.stiffness < 10    ? 2
                                                     : m.stiffness < 100 ? 1
                                                                         : 0)));
  const std::string source = ToString(m.source);
  row.push_back(fmt::format("<span class=\"source-{0}\">{0}</span>", EscapeHtml(source)));
  return row;
}

}  // namespace

Section BuildBranchesSection(PageContext& page) {
  Section s{"branches", "Simulation-ready tree", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFile("build/simready.json")) {
    s.Missing("build/simready.json is not in the result: no simulation-ready tree was built.");
    return s;
  }
  Tree tree;
  try {
    tree = ReadTreeJson(folder.Path("build/simready.json"));
  } catch (const Error& e) {
    s.LeftOut(std::string("build/simready.json could not be read: ") + e.what());
    return s;
  }
  s.present = true;
  s.html += TreeFactsTable(Summarize(tree));
  HtmlTable table(
      {"id", "parent", "level", "length (m)", "base radius (mm)", "f bend u (Hz)", "f bend w (Hz)",
       "f twist (Hz)", "\xCE\xB6 bend u", "\xCE\xB6 bend w", "\xCE\xB6 twist", "k (N/m)", "source"},
      "branches");
  const int rows = std::min(tree.size(), page.options().max_branch_rows);
  for (int i = 0; i < rows; ++i) table.AddHtmlRow(BranchRow(tree.branches[i]));
  s.html += "<div class=\"scroll\">\n" + table.Html() + "</div>\n";
  if (rows < tree.size()) {
    s.LeftOut(fmt::format("The table lists the first {} of {} branches.", rows, tree.size()));
  }
  return s;
}

}  // namespace simtree::report
