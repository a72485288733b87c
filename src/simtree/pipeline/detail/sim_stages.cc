// The simulation side: build (the simulation-ready tree with the placed markers), simulate (the
// capture's pull, replayed), render (beside the capture's frames), report.

#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/tree_json.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/simulation_json.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/branch_stiffness.h"
#include "simtree/pipeline/detail/placements.h"
#include "simtree/pipeline/detail/pull_fit.h"
#include "simtree/pipeline/detail/stage_functions.h"
#include "simtree/pipeline/run.h"
#include "simtree/registration/registration_report.h"
#include "simtree/report/report.h"
#include "simtree/simready/build.h"
#include "simtree/viewer/render.h"

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace simtree::pipeline::detail {
namespace {

Eigen::Isometry3d PullCamera(const StageContext& context) {
  const fs::path path = context.Result("register/pull_camera.json");
  const std::optional<Eigen::Isometry3d> camera = registration::ReadPullCameraJson(path);
  if (!camera) throw InputError(path.string(), "placed", "expected a placed pull camera");
  return *camera;
}

// simulation.json, as `simtree simulate` writes it, plus the pull fit.
ojson Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// simulation.json's "pull_fit": the held-pose fit, and the motion fit when it ran.
ojson PullFitJson(const PullFit& fit) {
  ojson out = {{"force", Vec(fit.force)},
               {"residual_rms_m", fit.residual_rms_m},
               {"observed_rms_m", fit.observed_rms_m},
               {"markers", fit.markers},
               {"candidates", fit.candidates},
               {"detected_release_s", fit.detected_release_s}};
  if (fit.motion.fitted) {
    out["motion"] = {{"release_s", fit.motion.release_s},
                     {"time_step_s", fit.motion.time_step_s},
                     {"residual_rms_m", fit.motion.residual_rms_m},
                     {"observed_rms_m", fit.motion.observed_rms_m},
                     {"markers", fit.motion.markers},
                     {"samples", fit.motion.samples}};
  }
  return out;
}

dynamics::SimulationJsonContent SimulationRecord(const Tree& tree,
                                                 const dynamics::SimulationOptions& sim,
                                                 const dynamics::SimulationResult& result,
                                                 const PullFit& fit) {
  dynamics::SimulationJsonContent content = dynamics::DescribeSimulation(tree, sim, result);
  content.tree_file = "build/simready.json";
  content.record_model = false;
  content.pull_fit = PullFitJson(fit);
  content.markers = tree.markers.size();
  content.outputs = {"nodes.bin", "markers.csv", "markers.json", "animation.glb",
                     "simulation.json"};
  return content;
}

// build/calibration.json: the stiffness factor chosen and every factor tried.
ojson CalibrationJson(const StiffnessCalibration& calibration) {
  ojson trials = ojson::array();
  for (const StiffnessTrial& t : calibration.trials) {
    trials.push_back({{"factor", t.factor},
                      {"replay_residual_rms_m",
                       std::isfinite(t.residual_rms_m) ? ojson(t.residual_rms_m) : ojson()}});
  }
  return {{"format", "simtree.stiffness_calibration"},
          {"version", 1},
          {"levels", "branches of level >= 1 (every branch above the trunk)"},
          {"frequency_factor", calibration.factor},
          {"stiffness_factor", calibration.factor * calibration.factor},
          {"trials", trials}};
}

double ChosenResidual(const StiffnessCalibration& calibration) {
  for (const StiffnessTrial& t : calibration.trials) {
    if (t.factor == calibration.factor) return t.residual_rms_m;
  }
  return std::nan("");
}

// The run simulate wrote: its schedule and length, read back from simulation.json.
dynamics::SimulationOptions SimulationFromJson(const fs::path& path) {
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, "simtree.simulation", 1);
  dynamics::SimulationOptions sim;
  sim.duration_s = doc.Number("duration_s");
  sim.fps = doc.Number("fps");
  const JsonNode pull = doc.Field("pull");
  dynamics::PullSchedule schedule;
  schedule.rope.branch = pull.Integer("branch");
  schedule.rope.arc_length = pull.Number("arc_length_m");
  schedule.rope.anchor = pull.Vector3("anchor");
  schedule.rope.force_n = pull.Number("force_n");
  schedule.hold_s = pull.Number("hold_s");
  schedule.release_s = pull.Number("release_s");
  sim.pull = schedule;
  return sim;
}

}  // namespace

std::string RunBuildStage(const StageContext& context) {
  const Placements placements = ReadPlacements(context.Result("identify/placements.json"));
  const Tree static_tree =
      WithMarkers(ReadTreeJson(context.Result("reconstruct/static.json")), placements);
  const identification::MaterialsFile materials =
      identification::ReadMaterialsJson(context.Result("identify/materials.json"));
  simready::BuildReport report;
  const Tree identified = simready::BuildSimulationReadyTree(static_tree, materials, {}, &report);
  const Trajectories tracks = ReadTrajectoriesCsv(context.Result("track/trajectories.csv"));
  const StiffnessCalibration calibration =
      CalibrateBranchStiffness(identified, tracks, PullCamera(context), materials.release_time_s,
                               placements.held_out, PullFitOptions{});
  const Tree tree = StiffenBranches(identified, calibration.factor);
  WriteTreeJson(tree, context.out_dir / "simready.json");
  WriteFileAtomically(context.out_dir / "calibration.json",
                      CalibrationJson(calibration).dump(2) + "\n");
  return fmt::format(
      "{} branches: {} measured, {} interpolated; {} markers; {:.1f} kg; branches above the "
      "trunk x{:.2f} in frequency to replay the pull ({:.1f} mm RMS; x{:.2f}: {:.1f} mm)",
      tree.size(), report.measured, report.interpolated, tree.markers.size(), report.total_mass_kg,
      calibration.factor, 1e3 * ChosenResidual(calibration), calibration.trials.front().factor,
      1e3 * calibration.trials.front().residual_rms_m);
}

std::string RunSimulateStage(const StageContext& context) {
  const Tree tree = ReadTreeJson(context.Result("build/simready.json"));
  const Trajectories tracks = ReadTrajectoriesCsv(context.Result("track/trajectories.csv"));
  const identification::MaterialsFile materials =
      identification::ReadMaterialsJson(context.Result("identify/materials.json"));
  const Placements placements = ReadPlacements(context.Result("identify/placements.json"));
  const PullFitOptions fit_options;
  const PullFit fit = FitPull(tree, tracks, PullCamera(context), materials.release_time_s,
                              placements.held_out, fit_options);

  dynamics::SimulationOptions sim;
  sim.duration_s = tracks.times_s.back();
  sim.fps = materials.frame_rate_hz > 0 ? materials.frame_rate_hz : 30.0;
  sim.pull = fit.Schedule(fit_options.anchor_distance_m);
  if (fit.motion.fitted) sim.max_time_step_s = fit.motion.time_step_s;  // the step it was fitted at
  dynamics::ValidateSimulation(tree, sim);
  const fs::path& dir = context.out_dir;
  dynamics::NodeFrameWriter nodes(dir / "nodes.bin");
  dynamics::MarkerTrackWriter markers(tree.markers, dir / "markers.csv", dir / "markers.json");
  dynamics::AnimationRecorder animation(dir / "animation.glb", tree.markers);
  dynamics::FrameRecorder* recorders[] = {&nodes, &markers, &animation};
  const dynamics::SimulationResult result = dynamics::RunSimulation(tree, sim, recorders);
  dynamics::WriteSimulationJson(SimulationRecord(tree, sim, result, fit), dir / "simulation.json");
  const MotionFit& motion = fit.motion;
  return fmt::format(
      "pull {:.1f} N on branch {} at {:.2f} m (held pose fit {:.1f} of {:.1f} mm RMS, motion fit "
      "{} of {} mm RMS on {} markers), held {:.2f} s, released {:.3f} s (detected {:.3f} s); {} "
      "frames",
      fit.force.norm(), fit.branch, fit.arc_length, 1e3 * fit.residual_rms_m,
      1e3 * fit.observed_rms_m,
      motion.fitted ? fmt::format("{:.1f}", 1e3 * motion.residual_rms_m) : "-",
      motion.fitted ? fmt::format("{:.1f}", 1e3 * motion.observed_rms_m) : "-",
      motion.fitted ? motion.markers : fit.markers, fit.hold_s, fit.release_s,
      fit.detected_release_s, result.frames);
}

std::string RunRenderStage(const StageContext& context) {
  const Tree tree = ReadTreeJson(context.Result("build/simready.json"));
  const dynamics::SimulationOptions sim =
      SimulationFromJson(context.Result("simulate/simulation.json"));
  viewer::RenderOptions options;
  options.capture = context.capture_dir;
  options.world_from_camera = PullCamera(context);
  options.width = context.options.render_width;
  options.height = context.options.render_width * 9 / 16;
  const viewer::RenderResult result =
      viewer::RenderSimulation(tree, sim, nullptr, {}, options, context.out_dir);
  return fmt::format("{} side-by-side frames of {}x{} ({})", result.frames, result.width,
                     result.height, result.backend);
}

std::string RunReportStage(const StageContext& context) {
  report::ReportOptions options;
  options.allow_missing_javascript = context.options.allow_missing_javascript;
  const report::ReportResult result = report::WriteReport(context.result_dir, options);
  for (const std::string& note : result.notes) spdlog::debug("report: {}", note);
  return fmt::format("report.html, {:.1f} MB ({} notes)", result.bytes / 1e6, result.notes.size());
}

}  // namespace simtree::pipeline::detail
