// The views: preprocess.json's numbers per view, each view's clean cloud as its camera saw it,
// and the capture's contact sheet when run.json names a capture that is still there.

#include <map>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/report/detail/cloud_thumbnail.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

// preprocess.json's counts per view (its reader keeps the clouds, not the counts), by name.
std::map<std::string, nlohmann::json> ViewNumbers(const ResultFolder& folder) {
  std::map<std::string, nlohmann::json> numbers;
  const JsonDocument doc = ReadJsonDocument(folder.Path("preprocess/preprocess.json"));
  if (const auto views = FindValue(doc.root(), "views")) {
    for (const JsonNode& v : views->Items()) {
      if (const auto name = FindValue(v, "name")) numbers[name->String()] = v.json();
    }
  }
  return numbers;
}

std::string Count(const std::map<std::string, nlohmann::json>& numbers, const std::string& view,
                  const char* key, int digits = 0) {
  const auto it = numbers.find(view);
  if (it == numbers.end() || !it->second.contains(key) || !it->second[key].is_number()) return "";
  return FormatNumber(it->second[key].get<double>(), digits);
}

void AddViewTable(const ResultFolder& folder,
                  const std::vector<preprocessing::PreprocessedView>& views, Section& s) {
  const auto numbers = ViewNumbers(folder);
  HtmlTable table({"view", "input points", "tree points", "point spacing (mm)", "voxel (mm)",
                   "ground", "time (s)", "problem"});
  for (const preprocessing::PreprocessedView& v : views) {
    if (!v.result) {
      table.AddRow({v.name, Count(numbers, v.name, "input_points"), "", "", "", "", "", v.failure});
      continue;
    }
    const preprocessing::PreprocessResult& r = *v.result;
    table.AddRow({v.name, Count(numbers, v.name, "input_points"),
                  std::to_string(r.cloud.points_.size()), FormatNumber(1000 * r.point_spacing_m, 1),
                  FormatNumber(1000 * r.voxel_size_m, 1), r.ground ? "found" : "none",
                  Count(numbers, v.name, "seconds", 2), ""});
  }
  s.html += table.Html();
}

void AddThumbnails(PageContext& page, const std::vector<preprocessing::PreprocessedView>& views,
                   Section& s) {
  std::string figures;
  for (const preprocessing::PreprocessedView& v : views) {
    if (!v.result) continue;
    const RgbImage image = CloudThumbnail(v.result->cloud.points_, 220, 280);
    figures += page.FigureOf(image, v.name, v.name, s, 220);
  }
  if (!figures.empty()) {
    s.html += "<div class=\"gallery\">\n" + figures + "</div>\n";
    s.Remark("Each view's clean tree cloud as its camera saw it (x right, y down), darker nearer.");
  }
}

}  // namespace

Section BuildViewsSection(PageContext& page) {
  Section s{"views", "Views", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFile("preprocess/preprocess.json")) {
    s.Missing("preprocess/preprocess.json is not in the result: the views were not preprocessed.");
  } else {
    try {
      const auto views = preprocessing::ReadPreprocessedViews(folder.Path("preprocess"));
      s.present = true;
      AddViewTable(folder, views, s);
      AddThumbnails(page, views, s);
    } catch (const Error& e) {
      s.LeftOut(std::string("preprocess/ could not be read: ") + e.what());
    }
  }
  if (!folder.capture.empty() &&
      std::filesystem::is_regular_file(folder.capture / "contact_sheet.png")) {
    s.present = true;
    s.html +=
        page.Figure(folder.capture / "contact_sheet.png",
                    "The capture's views: colour and false-colour depth (contact_sheet.png).", s);
  } else if (folder.run && !folder.run->capture.empty() && folder.capture.empty()) {
    s.Remark(
        fmt::format("The capture {} named by run.json is not reachable from here; its "
                    "pictures are not shown.",
                    folder.run->capture));
  }
  return s;
}

}  // namespace simtree::report
