// The paper's tables (I-II registration, III tracking, IV materials) with this run's numbers
// beside them: registration from pairs.json, materials from materials.json, tracking from
// eval/eval.json when it scored the tracker against the truth.

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/tree_json.h"
#include "simtree/identification/materials_file.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void AddRegistrationTable(const ResultFolder& folder, Section& s) {
  HtmlTable table({"", "time (ms)", "RMSE (mm)", "match rate"}, "paper");
  table.AddRow({"paper Table I: (ours) key region skeleton, coarse", "963", "11.56", "66.04 %"});
  const char* rows[][4] = {{"36\xC2\xB0", "4179", "11.01", "67.16 %"},
                           {"72\xC2\xB0", "6890", "11.07", "55.89 %"},
                           {"108\xC2\xB0", "7858", "11.85", "44.70 %"},
                           {"144\xC2\xB0", "10271", "12.14", "21.59 %"}};
  for (const auto& r : rows) {
    table.AddRow({fmt::format("paper Table II: ours, views {} apart", r[0]), r[1], r[2], r[3]});
  }
  if (folder.HasFile("register/pairs.json")) {
    try {
      const JsonDocument doc = ReadJsonDocument(folder.Path("register/pairs.json"));
      std::vector<double> time, rmse, rate;
      for (const JsonNode& p : doc.root().Field("pairs").Items()) {
        if (auto ok = FindValue(p, "ok"); ok && !ok->Bool()) continue;
        if (auto v = FindValue(p, "time_ms")) time.push_back(v->Number());
        if (auto v = FindValue(p, "rmse_mm")) rmse.push_back(v->Number());
        if (auto v = FindValue(p, "match_rate")) rate.push_back(100 * v->Number());
      }
      table.AddHtmlRow(
          {"<b>" + EscapeHtml(fmt::format("this run: median of {} pairs", time.size())) + "</b>",
           FormatNumber(Median(time), 0), FormatNumber(Median(rmse), 2),
           FormatNumber(Median(rate), 2) + " %"},
          "this-run");
    } catch (const Error& e) {
      s.LeftOut(std::string("register/pairs.json could not be read: ") + e.what());
    }
  } else {
    s.Missing("This run's registration row needs register/pairs.json.");
  }
  s.html += "<h3>Registration (paper Tables I and II)</h3>\n" + table.Html();
}

// The first object in `doc` (depth first) that has every key of one of the name lists.
const nlohmann::json* FindObjectWith(const nlohmann::json& doc,
                                     const std::vector<std::string>& keys) {
  if (doc.is_object()) {
    if (std::all_of(keys.begin(), keys.end(), [&](const auto& k) { return doc.contains(k); })) {
      return &doc;
    }
  }
  if (doc.is_object() || doc.is_array()) {
    for (const auto& child : doc) {
      if (const nlohmann::json* found = FindObjectWith(child, keys)) return found;
    }
  }
  return nullptr;
}

std::string Field(const nlohmann::json& obj, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    if (obj.contains(n) && obj[n].is_number()) return FormatNumber(obj[n].get<double>(), 3);
  }
  return FormatNumber(std::nan(""), 0);
}

void AddTrackingTable(const ResultFolder& folder, Section& s) {
  HtmlTable table({"", "success rate", "precision", "recall", "F-score"}, "paper");
  table.AddRow({"paper Table III: ATOM", "0.736", "0.773", "0.769", "0.755"});
  table.AddRow({"paper Table III: DiMP", "0.729", "0.809", "0.832", "0.820"});
  table.AddRow({"paper Table III: DeT", "0.818", "0.807", "0.851", "0.849"});
  const nlohmann::json* scores = nullptr;
  nlohmann::json eval;
  if (folder.HasFile("eval/eval.json")) {
    try {
      eval = ReadJsonDocument(folder.Path("eval/eval.json")).value;
      const nlohmann::json& tracking = eval.contains("tracking") ? eval["tracking"] : eval;
      scores = FindObjectWith(tracking, {"precision", "recall"});
    } catch (const Error&) {
    }
  }
  if (scores) {
    table.AddHtmlRow({"<b>this run (eval.json, against the truth)</b>",
                      Field(*scores, {"success_rate", "success"}), Field(*scores, {"precision"}),
                      Field(*scores, {"recall"}), Field(*scores, {"f_score", "fscore", "f1"})},
                     "this-run");
  }
  s.html += "<h3>Tracking (paper Table III)</h3>\n" + table.Html();
  if (!scores) {
    s.Missing("This run's tracking row needs eval/eval.json with tracking scores (the truth).");
  }
}

std::string SpeciesOf(const ResultFolder& folder) {
  for (const char* file : {"build/simready.json", "reconstruct/static.json"}) {
    if (!folder.HasFile(file)) continue;
    try {
      const std::string species = ReadTreeJson(folder.Path(file)).metadata.species;
      if (!species.empty()) return species;
    } catch (const Error&) {
    }
  }
  return "";
}

void AddMaterialsTable(const ResultFolder& folder, Section& s) {
  HtmlTable table({"tree species", "natural frequency f (Hz)", "damping ratio \xCE\xB6"}, "paper");
  table.AddRow({"paper Table IV: Acer palmatum", "1.07~1.50", "0.031~0.060"});
  table.AddRow({"paper Table IV: Magnolia", "0.72~1.19", "0.023~0.033"});
  table.AddRow({"paper Table IV: Acer rubrum", "0.93~1.50", "0.022~0.056"});
  if (folder.HasFile("identify/materials.json")) {
    try {
      const auto m = identification::ReadMaterialsJson(folder.Path("identify/materials.json"));
      const std::string species = SpeciesOf(folder);
      table.AddHtmlRow(
          {"<b>" + EscapeHtml("this run" + (species.empty() ? "" : ": " + species)) + "</b>",
           FormatNumber(m.ranges.min_frequency_hz, 2) + "~" +
               FormatNumber(m.ranges.max_frequency_hz, 2),
           FormatNumber(m.ranges.min_damping, 3) + "~" + FormatNumber(m.ranges.max_damping, 3)},
          "this-run");
    } catch (const Error& e) {
      s.LeftOut(std::string("identify/materials.json could not be read: ") + e.what());
    }
  } else {
    s.Missing("This run's materials row needs identify/materials.json.");
  }
  s.html += "<h3>Materials (paper Table IV)</h3>\n" + table.Html();
}

}  // namespace

Section BuildPaperTablesSection(PageContext& page) {
  Section s{"paper", "The paper's tables", "", true, {}};
  s.html +=
      "<p>The paper's numbers (real trees, its own setup) beside this run's. They are not "
      "the same experiment: read them as orders of magnitude. The scores against the truth "
      "are in the next section when eval ran.</p>\n";
  AddRegistrationTable(page.folder(), s);
  AddTrackingTable(page.folder(), s);
  AddMaterialsTable(page.folder(), s);
  return s;
}

}  // namespace simtree::report
