// Identification: materials.json's record and Table IV-style ranges, every link's values, and the
// links' spectra as interactive charts with the identified frequency marked.

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/trajectories.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/link_spectra.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

namespace id = simtree::identification;

void AddRecord(const id::MaterialsFile& m, Section& s) {
  HtmlTable table({"", ""}, "facts");
  table.AddRow({"estimator", ToString(m.estimator)});
  table.AddRow({"release", fmt::format("{} s ({})", FormatNumber(m.release_time_s, 3),
                                       m.release_detected ? "detected" : "given")});
  table.AddRow({"free decay used", fmt::format("{} - {} s", FormatNumber(m.window_start_s, 3),
                                               FormatNumber(m.window_end_s, 3))});
  table.AddRow({"frame rate", FormatNumber(m.frame_rate_hz, 2) + " Hz"});
  const id::MaterialRanges& r = m.ranges;
  table.AddRow({"links measured", fmt::format("{} of {}", r.measured, r.links)});
  table.AddRow({"natural frequency f (Hz)",
                fmt::format("{}~{} ({} values within {:.0f}%)", FormatNumber(r.min_frequency_hz, 2),
                            FormatNumber(r.max_frequency_hz, 2), r.frequency_count,
                            100 * r.bounds.max_frequency_relative_std)});
  table.AddRow(
      {"damping ratio", fmt::format("{}~{} ({} values within {:.0f}%)",
                                    FormatNumber(r.min_damping, 3), FormatNumber(r.max_damping, 3),
                                    r.damping_count, 100 * r.bounds.max_damping_relative_std)});
  if (!r.uncertain.empty()) {
    std::string labels;
    for (const std::string& l : r.uncertain) labels += (labels.empty() ? "" : ", ") + l;
    table.AddRow({"uncertain links (left out of the ranges)", labels});
  }
  s.html += table.Html();
}

void AddLinks(const id::MaterialsFile& m, Section& s) {
  HtmlTable table({"link", "kind", "status", "f (Hz)", "\xCE\xB6", "f std (Hz)", "\xCE\xB6 std",
                   "branch", "message"});
  for (const id::LinkMaterial& l : m.links) {
    table.AddRow({l.label, id::ToString(l.kind), id::ToString(l.value.status),
                  FormatNumber(l.value.frequency_hz, 3), FormatNumber(l.value.damping_ratio, 4),
                  FormatNumber(l.value.frequency_std_hz, 4), FormatNumber(l.value.damping_std, 4),
                  l.branch ? std::to_string(*l.branch) : "", l.value.message});
  }
  s.html += "<h3>Links</h3>\n" + table.Html();
}

void AddSpectra(PageContext& page, const id::MaterialsFile& m, Section& s) {
  const std::filesystem::path file = page.folder().TrajectoriesFile();
  if (file.empty()) {
    s.Missing("The spectra need the trajectories, which are not in the result.");
    return;
  }
  std::vector<LinkSpectrum> spectra;
  try {
    spectra = ComputeLinkSpectra(ReadTrajectoriesCsv(file), m, page.options().max_chart_samples);
  } catch (const Error& e) {
    s.LeftOut(std::string("The spectra could not be computed: ") + e.what());
    return;
  }
  s.html +=
      "<h3>Spectra</h3>\n<p>Amplitude spectra of each link's deflection over the free decay "
      "(zero-padded 8x, both bending planes); the dashed line is the identified "
      "frequency.</p>\n";
  if (!page.scripts()) {
    s.LeftOut("The spectra charts need the JavaScript libraries, which are not in this page.");
    return;
  }
  page.SetData("spectra", SpectraJson(spectra));
  s.html += "<div class=\"chart-grid\">\n";
  for (size_t i = 0; i < spectra.size(); ++i) {
    s.html += fmt::format(
        "<div class=\"chart-box small\"><canvas id=\"chart-spectrum-{}\">"
        "</canvas></div>\n",
        i);
    if (!spectra[i].problem.empty()) {
      s.notes.push_back(fmt::format("{}: no spectrum ({})", spectra[i].label, spectra[i].problem));
    }
  }
  s.html += "</div>\n";
}

}  // namespace

Section BuildIdentificationSection(PageContext& page) {
  Section s{"identification", "Identification", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFile("identify/materials.json")) {
    s.Missing("identify/materials.json is not in the result: no materials were identified.");
    return s;
  }
  id::MaterialsFile materials;
  try {
    materials = id::ReadMaterialsJson(folder.Path("identify/materials.json"));
  } catch (const Error& e) {
    s.LeftOut(std::string("identify/materials.json could not be read: ") + e.what());
    return s;
  }
  s.present = true;
  AddRecord(materials, s);
  AddSpectra(page, materials, s);
  AddLinks(materials, s);
  return s;
}

}  // namespace simtree::report
