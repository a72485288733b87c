#include "simtree/report/detail/tree_facts.h"

#include <fmt/format.h>

#include "simtree/report/detail/html.h"

namespace simtree::report {

std::string TreeFactsTable(const TreeSummary& t) {
  HtmlTable table({"", ""}, "facts");
  std::string levels;
  for (size_t l = 0; l < t.branches_per_level.size(); ++l) {
    levels += fmt::format("{}{}: {}", l ? ", " : "", l, t.branches_per_level[l]);
  }
  table.AddRow({"branches", fmt::format("{} (by level {})", t.branches, levels)});
  table.AddRow({"nodes", std::to_string(t.nodes)});
  table.AddRow({"height", FormatNumber(t.height_m, 2) + " m"});
  table.AddRow({"trunk base radius", FormatNumber(100 * t.trunk_base_radius_m, 1) + " cm"});
  table.AddRow({"branch length in all", FormatNumber(t.total_length_m, 1) + " m"});
  table.AddRow({"markers", std::to_string(t.markers)});
  if (t.with_material > 0) {
    table.AddRow({"materials", fmt::format("{} of {} branches ({})", t.with_material, t.branches,
                                           FormatMaterialSources(t))});
    table.AddRow(
        {"natural frequency", fmt::format("{} - {} Hz", FormatNumber(t.min_frequency_hz, 2),
                                          FormatNumber(t.max_frequency_hz, 2))});
    table.AddRow({"damping ratio", fmt::format("{} - {}", FormatNumber(t.min_damping, 4),
                                               FormatNumber(t.max_damping, 4))});
  }
  return table.Html();
}

}  // namespace simtree::report
