#include "simtree/registration/registration_report.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/json_util.h"
#include "simtree/io/ground_truth.h"
#include "simtree/registration/detail/cloud_picture.h"

namespace simtree::registration {
namespace {

// NaN and infinity are not JSON: they become null.
nlohmann::ordered_json Number(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

double Round(double value, double unit) { return std::round(value / unit) * unit; }

constexpr const char* kFrame =
    "registration frame: Z up (the anchor view's ground normal, else its trunk axis), origin at "
    "the foot of the anchor view's trunk, Y along the anchor camera's view; metres";

}  // namespace

nlohmann::ordered_json PosesToJson(const MultiViewResult& result) {
  nlohmann::ordered_json doc;
  doc["format"] = kRegistrationFormat;
  doc["version"] = kRegistrationFormatVersion;
  doc["frame"] = kFrame;
  doc["anchor"] = result.views.empty() ? "" : result.views[result.anchor].name;
  doc["registered"] = result.RegisteredCount();
  doc["views_total"] = result.views.size();
  nlohmann::ordered_json views = nlohmann::ordered_json::array();
  for (const ViewRegistration& view : result.views) {
    nlohmann::ordered_json v;
    v["name"] = view.name;
    v["registered"] = view.registered();
    v["verified"] = view.verified();
    v["status"] = view.status;
    v["pairs"] = view.pairs;
    v["frame_from_camera"] =
        view.registered() ? PoseToJson(view.frame_from_camera) : nlohmann::ordered_json(nullptr);
    views.push_back(v);
  }
  doc["views"] = views;
  return doc;
}

nlohmann::ordered_json PairsToJson(const MultiViewResult& result) {
  nlohmann::ordered_json doc;
  doc["format"] = "simtree.registration_pairs";
  doc["version"] = kRegistrationFormatVersion;
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const PairEdge& edge : result.pairs) {
    const PairResult& r = edge.result;
    nlohmann::ordered_json p;
    p["source"] = r.source;
    p["target"] = r.target;
    p["ok"] = r.ok();
    p["status"] = r.status;
    p["used"] = edge.used;
    p["consistent"] = edge.consistent;
    p["time_ms"] = Round(1e3 * r.seconds, 0.1);
    p["coarse_time_ms"] = Round(1e3 * r.coarse.seconds, 0.1);
    p["fine_time_ms"] = Round(1e3 * r.fine.seconds, 0.1);
    p["rmse_mm"] = Round(1e3 * r.rmse_m, 0.01);
    p["match_rate"] = Round(r.match_rate, 1e-4);
    p["fitness"] = Round(r.fine.fitness, 1e-4);
    p["skeleton_overlap"] = Round(r.coarse_overlap, 1e-4);
    p["view_overlap"] = Round(r.view_overlap, 1e-4);
    p["up_disagreement_deg"] = Number(r.up_disagreement_deg);
    p["ground_offset_mm"] = Number(1e3 * r.ground_offset_m);
    p["trunk_offset_mm"] = Number(1e3 * r.trunk_offset_m);
    p["attempt"] = ToString(r.attempt);
    nlohmann::ordered_json attempts = nlohmann::ordered_json::array();
    for (const PairResult::AttemptRun& run : r.attempts) {
      attempts.push_back({{"attempt", ToString(run.attempt)},
                          {"view_overlap", Round(run.view_overlap, 1e-4)},
                          {"time_ms", Round(1e3 * run.seconds, 0.1)}});
    }
    p["attempts"] = attempts;
    p["declined"] = r.declined;
    p["trunk_constraint"] = r.trunk_constraint;
    p["ground_constraint"] = r.ground_constraint;
    p["pose_graph_rotation_residual_deg"] = Number(edge.used ? edge.rotation_residual_deg : NAN);
    p["pose_graph_shift_residual_mm"] = Number(edge.used ? 1e3 * edge.shift_residual_m : NAN);
    p["target_from_source"] = PoseToJson(r.target_from_source);
    pairs.push_back(p);
  }
  doc["pairs"] = pairs;
  return doc;
}

std::string PairsMarkdown(const MultiViewResult& result) {
  std::string out =
      "| source | target | status | time (ms) | RMSE (mm) | match rate | skeleton overlap | in "
      "pose "
      "graph |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const PairEdge& edge : result.pairs) {
    const PairResult& r = edge.result;
    const char* graph = !edge.used ? "no" : (edge.consistent ? "yes" : "inconsistent");
    out += fmt::format("| {} | {} | {} | {:.0f} | {:.2f} | {:.1f}% | {:.0f}% | {} |\n", r.source,
                       r.target, r.ok() ? "ok" : "FAILED: " + r.status, 1e3 * r.seconds,
                       1e3 * r.rmse_m, 100 * r.match_rate, 100 * r.coarse_overlap, graph);
  }
  out += fmt::format("\n{} of {} views registered (anchor {}).\n", result.RegisteredCount(),
                     result.views.size(),
                     result.views.empty() ? "-" : result.views[result.anchor].name);
  for (const ViewRegistration& view : result.views) {
    if (!view.registered()) out += fmt::format("- {} left out: {}\n", view.name, view.status);
  }
  return out;
}

nlohmann::ordered_json ExtraViewToJson(const ExtraViewResult& extra) {
  nlohmann::ordered_json doc;
  doc["format"] = kPullCameraFormat;
  doc["version"] = kPullCameraFormatVersion;
  doc["frame"] = kFrame;
  doc["view"] = extra.name;
  doc["placed"] = extra.placed();
  doc["outcome"] = ToString(extra.outcome);
  doc["status"] = extra.status;
  doc["frame_from_camera"] =
      extra.placed() ? PoseToJson(extra.frame_from_camera) : nlohmann::ordered_json(nullptr);
  doc["pairs_used"] = extra.pairs_used;
  doc["rotation_spread_deg"] = Number(extra.rotation_spread_deg);
  doc["shift_spread_mm"] = Number(1e3 * extra.shift_spread_m);
  doc["view_overlap"] = Round(extra.view_overlap, 1e-4);
  doc["seconds"] = Round(extra.seconds, 1e-3);
  nlohmann::ordered_json pairs = nlohmann::ordered_json::array();
  for (const ExtraViewPair& pair : extra.pairs) {
    const PairResult& r = pair.result;
    pairs.push_back({{"target", r.target},
                     {"ok", r.ok()},
                     {"status", r.status},
                     {"used", pair.used},
                     {"view_overlap", Round(r.view_overlap, 1e-4)},
                     {"match_rate", Round(r.match_rate, 1e-4)},
                     {"rotation_residual_deg", Number(pair.rotation_residual_deg)},
                     {"shift_residual_mm", Number(1e3 * pair.shift_residual_m)},
                     {"target_from_source", PoseToJson(r.target_from_source)}});
  }
  doc["pairs"] = pairs;
  return doc;
}

std::optional<Eigen::Isometry3d> ReadPullCameraJson(const std::filesystem::path& path) {
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kPullCameraFormat, kPullCameraFormatVersion);
  if (!doc.Bool("placed")) return std::nullopt;
  return PoseFromJson(doc.Field("frame_from_camera"));
}

RgbImage BeforeAfterPicture(const std::vector<RegistrationView>& views,
                            const MultiViewResult& result) {
  std::vector<std::vector<Eigen::Vector3d>> before(views.size()), after(views.size());
  PicturePanel before_panel{"before: every view in its own camera frame", {}};
  PicturePanel after_panel{
      fmt::format("after: {} of {} views registered", result.RegisteredCount(), views.size()), {}};
  PictureOptions options;
  std::string missing;
  for (size_t v = 0; v < views.size(); ++v) {
    const auto color = ViewColor(static_cast<int>(v));
    options.legend.emplace_back(views[v].name, color);
    if (!views[v].cloud) continue;
    for (const auto& p : views[v].cloud->points_) before[v].push_back(result.frame_from_anchor * p);
    before_panel.layers.push_back({&before[v], color, 1});
    if (v < result.views.size() && result.views[v].registered()) {
      for (const auto& p : views[v].cloud->points_) {
        after[v].push_back(result.views[v].frame_from_camera * p);
      }
      after_panel.layers.push_back({&after[v], color, 1});
    } else {
      missing += (missing.empty() ? "" : ", ") + views[v].name;
    }
  }
  if (!missing.empty()) after_panel.title += " (left out: " + missing + ")";
  return DrawPanels({before_panel, after_panel}, options);
}

}  // namespace simtree::registration
