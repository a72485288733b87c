// The registration: the before/after picture, every view's status (poses.json), the pairs with the
// paper's columns (pairs.json) and whether the pull camera was registered (pull_camera.json).

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/report/detail/html.h"
#include "simtree/report/detail/sections.h"

namespace simtree::report {
namespace {

std::string Text(const JsonNode& node, const std::string& key) {
  const auto v = FindValue(node, key);
  if (!v) return "";
  if (v->json().is_string()) return v->String();
  if (v->json().is_boolean()) return v->Bool() ? "yes" : "no";
  return v->json().dump();
}

std::string Num(const JsonNode& node, const std::string& key, int digits, double scale = 1.0) {
  const auto v = FindValue(node, key);
  if (!v || !v->json().is_number()) return FormatNumber(std::nan(""), 0);
  return FormatNumber(scale * v->Number(), digits);
}

void AddPoses(const ResultFolder& folder, Section& s) {
  const JsonDocument doc = ReadJsonDocument(folder.Path("register/poses.json"));
  const JsonNode root = doc.root();
  s.html +=
      "<p>" +
      EscapeHtml(fmt::format("{} of {} views registered, anchor {}.", Text(root, "registered"),
                             Text(root, "views_total"), Text(root, "anchor"))) +
      "</p>\n";
  HtmlTable table({"view", "registered", "status", "pairs"});
  if (const auto views = FindValue(root, "views")) {
    for (const JsonNode& v : views->Items()) {
      table.AddRow({Text(v, "name"), Text(v, "registered"), Text(v, "status"), Text(v, "pairs")});
    }
  }
  s.html += table.Html();
}

void AddPairs(const ResultFolder& folder, Section& s) {
  const JsonDocument doc = ReadJsonDocument(folder.Path("register/pairs.json"));
  HtmlTable table(
      {"source", "target", "status", "time (ms)", "RMSE (mm)", "match rate", "in pose graph"});
  if (const auto pairs = FindValue(doc.root(), "pairs")) {
    for (const JsonNode& p : pairs->Items()) {
      table.AddRow({Text(p, "source"), Text(p, "target"), Text(p, "status"), Num(p, "time_ms", 0),
                    Num(p, "rmse_mm", 2), Num(p, "match_rate", 1, 100.0) + " %", Text(p, "used")});
    }
  }
  s.html += "<h3>Pairs (the paper's Table I-II columns)</h3>\n" + table.Html();
}

}  // namespace

Section BuildRegistrationSection(PageContext& page) {
  Section s{"registration", "Registration", "", false, {}};
  const ResultFolder& folder = page.folder();
  if (!folder.HasFolder("register")) {
    s.Missing("register/ is not in the result: the views were not registered.");
    return s;
  }
  s.present = true;
  if (folder.HasFile("register/before_after.png")) {
    s.html += page.Figure(folder.Path("register/before_after.png"),
                          "Before: every view in its own camera frame; after: registered.", s);
  } else {
    s.Missing("register/before_after.png is missing.");
  }
  const auto read = [&](const char* file, void (*add)(const ResultFolder&, Section&)) {
    if (!folder.HasFile(std::string("register/") + file)) {
      s.Missing(fmt::format("register/{} is missing.", file));
      return;
    }
    try {
      add(folder, s);
    } catch (const Error& e) {
      s.LeftOut(fmt::format("register/{} could not be read: {}", file, e.what()));
    }
  };
  read("poses.json", AddPoses);
  read("pairs.json", AddPairs);
  if (folder.HasFile("register/pull_camera.json")) {
    s.Remark(
        "pull_camera.json: the pull camera's first frame was registered to the scans, so the "
        "trajectories are placed in the tree's frame.");
  } else {
    s.Missing(
        "register/pull_camera.json is missing: the pull camera was not registered to the "
        "scans.");
  }
  return s;
}

}  // namespace simtree::report
