#include "simtree/eval/eval_run.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/core/tree_json.h"
#include "simtree/eval/identification_metrics.h"
#include "simtree/eval/reconstruction_metrics.h"
#include "simtree/eval/registration_metrics.h"
#include "simtree/eval/tracking_metrics.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"
#include "simtree/tracking/boxes_file.h"

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace simtree::eval {
namespace {

ojson Number(double v) { return std::isfinite(v) ? ojson(v) : ojson(nullptr); }

// What the scoring of every part shares.
struct Inputs {
  fs::path result, gt;
  Tree truth;
  std::vector<Eigen::Vector3d> tree_points;  // on the true tree, world
  std::map<std::string, Eigen::Isometry3d> true_views;
  // From register/: the anchor's name, every registered view's and the pull camera's pose.
  std::string anchor;
  std::map<std::string, Eigen::Isometry3d> frame_from_view;
  std::optional<Eigen::Isometry3d> frame_from_pull;
  // The registration frame in the truth's world (through the anchor view), when known.
  std::optional<Eigen::Isometry3d> world_from_frame;
};

void ReadRegistration(Inputs& in) {
  const fs::path poses = in.result / "register" / "poses.json";
  if (!fs::exists(poses)) return;
  const JsonDocument file = ReadJsonDocument(poses);
  const JsonNode doc = file.root();
  in.anchor = doc.String("anchor");
  for (const JsonNode& v : doc.Field("views").Items()) {
    if (!v.Bool("registered")) continue;
    in.frame_from_view[v.String("name")] = PoseFromJson(v.Field("frame_from_camera"));
  }
  const fs::path pull = in.result / "register" / "pull_camera.json";
  if (fs::exists(pull)) {
    const JsonDocument pull_file = ReadJsonDocument(pull);
    const JsonNode p = pull_file.root();
    if (p.Bool("placed")) in.frame_from_pull = PoseFromJson(p.Field("frame_from_camera"));
  }
  const auto a = in.frame_from_view.find(in.anchor);
  const auto t = in.true_views.find(in.anchor);
  if (a != in.frame_from_view.end() && t != in.true_views.end()) {
    in.world_from_frame = t->second * a->second.inverse();
  }
}

Inputs ReadInputs(const fs::path& result, const fs::path& capture) {
  Inputs in;
  in.result = result;
  in.gt = capture / "gt";
  if (!fs::is_directory(in.gt)) {
    throw InputError(capture.string(), "gt/",
                     "expected a synth capture with its ground truth (gt/), found none");
  }
  in.truth = ReadTreeJson(in.gt / "tree.json");
  in.tree_points = TreeSamplePoints(in.truth);
  for (const ViewPose& v : ReadScanPoses(in.gt / "scan_poses.json")) {
    in.true_views[v.name] = v.world_from_camera;
  }
  ReadRegistration(in);
  return in;
}

ojson PoseErrorJson(const PoseError& e) {
  return {{"rotation_deg", e.rotation_deg},
          {"tree_rms_m", e.tree_rms_m},
          {"tree_max_m", e.tree_max_m},
          {"within_2deg_2cm", e.Within()}};
}

ojson ScoreRegistration(const Inputs& in, std::string& md) {
  if (in.frame_from_view.empty() || !in.true_views.count(in.anchor)) {
    md += "## Registration\n\nnot scored: register/poses.json missing or without the anchor\n\n";
    return {{"scored", false}};
  }
  const Eigen::Isometry3d& frame_from_anchor = in.frame_from_view.at(in.anchor);
  const Eigen::Isometry3d& world_from_anchor = in.true_views.at(in.anchor);
  ojson views = ojson::array();
  md +=
      "## Registration (pose error at the true tree, relative to the anchor " + in.anchor +
      ")\n\n| view | rotation (deg) | tree RMS (mm) | tree max (mm) |\n| --- | --- | --- | --- |\n";
  for (const auto& [name, frame_from_view] : in.frame_from_view) {
    const auto truth = in.true_views.find(name);
    if (truth == in.true_views.end() || name == in.anchor) continue;
    const PoseError e = ViewPoseError(frame_from_view, frame_from_anchor, truth->second,
                                      world_from_anchor, in.tree_points);
    ojson v = PoseErrorJson(e);
    v["view"] = name;
    views.push_back(v);
    md += fmt::format("| {} | {:.2f} | {:.1f} | {:.1f} |\n", name, e.rotation_deg,
                      1e3 * e.tree_rms_m, 1e3 * e.tree_max_m);
  }
  ojson out = {{"scored", true}, {"anchor", in.anchor}, {"views", views}};
  const fs::path pull_truth = in.gt / "pull_camera.json";
  if (in.frame_from_pull && fs::exists(pull_truth)) {
    const PoseError e =
        ViewPoseError(*in.frame_from_pull, frame_from_anchor, ReadPullCamera(pull_truth),
                      world_from_anchor, in.tree_points);
    out["pull_camera"] = PoseErrorJson(e);
    md += fmt::format("| pull camera | {:.2f} | {:.1f} | {:.1f} |\n", e.rotation_deg,
                      1e3 * e.tree_rms_m, 1e3 * e.tree_max_m);
  } else {
    out["pull_camera"] = nullptr;
  }
  md += "\n";
  return out;
}

Tree Transformed(Tree tree, const Eigen::Isometry3d& t) {
  for (Branch& b : tree.branches) {
    for (Node& n : b.nodes) n.position = t * n.position;
  }
  for (Marker& m : tree.markers) m.position = t * m.position;
  return tree;
}

ojson ScoreReconstruction(const Inputs& in, std::string& md) {
  const fs::path path = in.result / "reconstruct" / "static.json";
  if (!fs::exists(path) || !in.world_from_frame) {
    md +=
        "## Reconstruction\n\nnot scored: reconstruct/static.json or the registration "
        "frame is missing\n\n";
    return {{"scored", false}};
  }
  const TruthScores s =
      ScoreAgainstTruth(Transformed(ReadTreeJson(path), *in.world_from_frame), in.truth);
  md += "## Reconstruction (in the truth's frame through the anchor view)\n\n";
  md += fmt::format(
      "| recall | precision | skeleton distance (mm) | radius error | trunk radius error |\n"
      "| --- | --- | --- | --- | --- |\n| {:.2f} ({} of {}) | {:.2f} ({} of {}) | {:.1f} | "
      "{:.2f} | {:.2f} |\n\n",
      s.recall, s.found, s.true_branches, s.precision, s.correct, s.reconstructed_branches,
      1e3 * s.mean_skeleton_distance_m, s.radius_error, s.trunk_radius_error);
  return {{"scored", true},
          {"recall", s.recall},
          {"precision", s.precision},
          {"true_branches", s.true_branches},
          {"found", s.found},
          {"reconstructed_branches", s.reconstructed_branches},
          {"correct", s.correct},
          {"mean_skeleton_distance_m", s.mean_skeleton_distance_m},
          {"radius_error", s.radius_error},
          {"trunk_radius_error", s.trunk_radius_error}};
}

ojson ScoreTrackingStage(const Inputs& in, std::string& md) {
  const fs::path boxes = in.result / "track" / "boxes.csv";
  if (!fs::exists(boxes) || !fs::exists(in.gt / "markers_2d.json")) {
    md +=
        "## Tracking\n\nnot scored: no track/boxes.csv (the trajectories were given with "
        "--tracks)\n\n";
    return {{"scored", false}};
  }
  const TrackingScores s = ScoreTracking(
      tracking::ReadBoxesCsv(boxes), ReadTrajectoriesCsv(in.result / "track" / "trajectories.csv"),
      ReadMarkers2d(in.gt / "markers_2d.json"), ReadTrajectoriesCsv(in.gt / "trajectories.csv"));
  md += "## Tracking (paper Table III)\n\n";
  md += fmt::format(
      "| success rate | precision | recall | F-score | visible samples tracked | median 3D error "
      "(mm) | identity swaps |\n| --- | --- | --- | --- | --- | --- | --- |\n"
      "| {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.2f} | {:.1f} | {} |\n\n",
      s.success_rate, s.precision, s.recall, s.f_score, s.tracked_fraction, s.median_error_mm,
      s.swap_events);
  return {{"scored", true},
          {"success_rate", s.success_rate},
          {"precision", s.precision},
          {"recall", s.recall},
          {"f_score", s.f_score},
          {"tracked_fraction", s.tracked_fraction},
          {"median_error_mm", Number(s.median_error_mm)},
          {"swap_events", s.swap_events}};
}

ojson ScoreIdentification(const Inputs& in, std::string& md) {
  const fs::path path = in.result / "identify" / "materials.json";
  if (!fs::exists(path) || !fs::exists(in.gt / "modal.json")) {
    md += "## Identification\n\nnot scored: identify/materials.json or gt/modal.json missing\n\n";
    return {{"scored", false}};
  }
  const LinkScores scores =
      ScoreLinks(identification::ReadMaterialsJson(path), ReadModalTruth(in.gt / "modal.json"));
  const ScoreSummary& s = scores.summary;
  md += "## Identification (links against the FEM truth, " + scores.estimator + ")\n\n";
  md += fmt::format(
      "| scored | not estimated | median frequency error | median damping error | max "
      "frequency error | max damping error |\n| --- | --- | --- | --- | --- | --- |\n"
      "| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} |\n\n",
      s.scored, s.not_estimated, s.median_frequency_error, s.median_damping_error,
      s.max_frequency_error, s.max_damping_error);
  return {{"scored", true},
          {"estimator", scores.estimator},
          {"links", s.scored},
          {"not_estimated", s.not_estimated},
          {"median_frequency_error", Number(s.median_frequency_error)},
          {"median_damping_error", Number(s.median_damping_error)},
          {"max_frequency_error", Number(s.max_frequency_error)},
          {"max_damping_error", Number(s.max_damping_error)}};
}

}  // namespace
}  // namespace simtree::eval

namespace simtree::eval {
namespace {

// A displacement signal (pull camera frame, metres) at given times.
struct Signal {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> d;
};

// The strongest frequency of `x` (mean removed) by a direct Fourier scan over the band.
double DominantFrequency(const std::vector<double>& t, const std::vector<double>& x, double lo,
                         double hi) {
  double mean = 0;
  for (double v : x) mean += v / x.size();
  double best = 0, best_f = std::nan("");
  for (double f = lo; f <= hi; f += 0.005) {
    double re = 0, im = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      re += (x[i] - mean) * std::cos(2 * std::numbers::pi * f * t[i]);
      im += (x[i] - mean) * std::sin(2 * std::numbers::pi * f * t[i]);
    }
    if (re * re + im * im > best) best = re * re + im * im, best_f = f;
  }
  return best_f;
}

// The damping ratio that takes the RMS of the first second to that of the last second.
double EnvelopeDecay(const std::vector<double>& t, const std::vector<double>& x, double f) {
  if (t.size() < 4 || !(f > 0)) return std::nan("");
  const double t0 = t.front(), t1 = t.back();
  double a = 0, b = 0;
  int na = 0, nb = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] <= t0 + 1.0) a += x[i] * x[i], ++na;
    if (t[i] >= t1 - 1.0) b += x[i] * x[i], ++nb;
  }
  if (na == 0 || nb == 0 || b <= 0) return std::nan("");
  const double ratio = std::sqrt((a / na) / (b / nb));
  return std::log(ratio) / (2 * std::numbers::pi * f * (t1 - t0 - 1.0));
}

// Displacements from the first frame over [start, end], the track taken by `rotation`.
Signal Displacements(const Trajectories& tracks, int marker, const Eigen::Matrix3d& rotation,
                     double start, double end) {
  Signal s;
  const MarkerTrack* track = tracks.Find(marker);
  if (!track || !track->valid[0]) return s;
  for (int f = 0; f < tracks.frame_count(); ++f) {
    const double t = tracks.times_s[f];
    if (t < start || t > end || !track->valid[f]) continue;
    s.t.push_back(t);
    s.d.push_back(rotation * (track->positions[f] - track->positions[0]));
  }
  return s;
}

// Simulated against true displacement at the true signal's times (nearest simulated frame).
ChainMarkerScore ScoreMarker(const Signal& truth, const Signal& sim, double fps,
                             const RunEvalOptions& o) {
  ChainMarkerScore s;
  std::vector<double> t, xt, xs;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& d : truth.d) cov += d * d.transpose();
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
  double err = 0, ref = 0;
  for (size_t i = 0; i < truth.t.size(); ++i) {
    const auto it = std::lower_bound(sim.t.begin(), sim.t.end(), truth.t[i] - 0.5 / fps);
    if (it == sim.t.end() || std::abs(*it - truth.t[i]) > 0.5 / fps) continue;
    const Eigen::Vector3d& d = sim.d[it - sim.t.begin()];
    err += (d - truth.d[i]).squaredNorm();
    ref += truth.d[i].squaredNorm();
    t.push_back(truth.t[i]);
    xt.push_back(axis.dot(truth.d[i]));
    xs.push_back(axis.dot(d));
  }
  s.samples = static_cast<int>(t.size());
  if (s.samples < 4 || ref <= 0) {
    s.nrmse = std::nan("");
    return s;
  }
  s.nrmse = std::sqrt(err / ref);
  s.true_rms_m = std::sqrt(ref / s.samples);
  s.true_frequency_hz = DominantFrequency(t, xt, o.min_frequency_hz, o.max_frequency_hz);
  s.simulated_frequency_hz = DominantFrequency(t, xs, o.min_frequency_hz, o.max_frequency_hz);
  s.true_decay = EnvelopeDecay(t, xt, s.true_frequency_hz);
  s.simulated_decay = EnvelopeDecay(t, xs, s.simulated_frequency_hz);
  return s;
}

// The simulated markers (world = registration frame) as a trajectories file.
Trajectories ReadSimulatedMarkers(const fs::path& path) {
  std::string text = ReadFile(path);
  const size_t eol = text.find('\n');
  text = "# simtree.trajectories v1 frame=camera units=m" + text.substr(eol);
  return ParseTrajectoriesCsv(text, path.string());
}

std::vector<int> HeldOutMarkers(const fs::path& placements) {
  const JsonDocument file = ReadJsonDocument(placements);
  std::vector<int> out;
  for (const JsonNode& id : file.root().Field("held_out").ExpectArray().Items()) {
    out.push_back(id.Integer());
  }
  return out;
}

std::vector<ChainMarkerScore> ScoreChainMarkers(const Inputs& in, const RunEvalOptions& o) {
  const Trajectories truth = ReadTrajectoriesCsv(in.gt / "trajectories.csv");
  const Trajectories sim = ReadSimulatedMarkers(in.result / "simulate" / "markers.csv");
  const double release = ReadPullLoad(in.gt / "pull_load.json").release_s;
  const double end = release + o.chain_window_s;
  const double fps = sim.frame_count() > 1
                         ? (sim.frame_count() - 1) / (sim.times_s.back() - sim.times_s.front())
                         : 30.0;
  // The simulation is in the registration frame: into the pull camera's by its estimated pose.
  const Eigen::Matrix3d camera_from_frame = in.frame_from_pull->linear().transpose();
  std::vector<ChainMarkerScore> out;
  for (int id : HeldOutMarkers(in.result / "identify" / "placements.json")) {
    const Signal t = Displacements(truth, id, Eigen::Matrix3d::Identity(), release, end);
    const Signal s = Displacements(sim, id, camera_from_frame, release, end);
    ChainMarkerScore score = ScoreMarker(t, s, fps, o);
    score.marker = id;
    score.label = fmt::format("M{}", id);
    out.push_back(score);
  }
  return out;
}

ojson ScoreChain(const Inputs& in, const RunEvalOptions& o, RunEvaluation& ev, std::string& md) {
  ev.chain_median_nrmse = std::nan("");
  if (!fs::exists(in.result / "simulate" / "markers.csv") ||
      !fs::exists(in.result / "identify" / "placements.json") || !in.frame_from_pull) {
    md +=
        "## Chain\n\nnot scored: simulate/markers.csv, identify/placements.json or the pull "
        "camera is missing\n\n";
    return {{"scored", false}};
  }
  ev.chain = ScoreChainMarkers(in, o);
  md += fmt::format(
      "## Chain: simulated held-out markers against the truth, {:.0f} s after the release\n\n"
      "| marker | samples | NRMSE | true RMS (mm) | frequency sim / true (Hz) | decay sim / "
      "true |\n| --- | --- | --- | --- | --- | --- |\n",
      o.chain_window_s);
  ojson markers = ojson::array();
  std::vector<double> values;
  for (const ChainMarkerScore& c : ev.chain) {
    if (std::isfinite(c.nrmse)) values.push_back(c.nrmse);
    markers.push_back({{"marker", c.marker},
                       {"samples", c.samples},
                       {"nrmse", Number(c.nrmse)},
                       {"true_rms_m", c.true_rms_m},
                       {"simulated_frequency_hz", Number(c.simulated_frequency_hz)},
                       {"true_frequency_hz", Number(c.true_frequency_hz)},
                       {"simulated_decay", Number(c.simulated_decay)},
                       {"true_decay", Number(c.true_decay)}});
    md += fmt::format("| {} | {} | {:.2f} | {:.1f} | {:.2f} / {:.2f} | {:.3f} / {:.3f} |\n",
                      c.label, c.samples, c.nrmse, 1e3 * c.true_rms_m, c.simulated_frequency_hz,
                      c.true_frequency_hz, c.simulated_decay, c.true_decay);
  }
  if (!values.empty()) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    ev.chain_median_nrmse = 0.5 * (values[(n - 1) / 2] + values[n / 2]);
  }
  md += fmt::format("\nmedian NRMSE {:.2f} (target <= 0.3)\n\n", ev.chain_median_nrmse);
  return {{"scored", true},
          {"window_s", o.chain_window_s},
          {"median_nrmse", Number(ev.chain_median_nrmse)},
          {"markers", markers}};
}

}  // namespace

void RunEvalOptions::Validate() const {
  if (!(chain_window_s > 0) || !std::isfinite(chain_window_s)) {
    throw InputError("run eval options", "chain_window_s", "expected seconds > 0");
  }
  if (!(min_frequency_hz > 0) || !(max_frequency_hz > min_frequency_hz)) {
    throw InputError("run eval options", "max_frequency_hz",
                     "expected 0 < min_frequency_hz < max_frequency_hz");
  }
}

RunEvaluation EvaluateRun(const fs::path& result_dir, const fs::path& capture_dir,
                          const RunEvalOptions& options) {
  options.Validate();
  if (!fs::is_directory(result_dir)) {
    throw InputError(result_dir.string(), "", "expected a result folder of `simtree run`");
  }
  const Inputs in = ReadInputs(result_dir, capture_dir);
  RunEvaluation ev;
  std::string& md = ev.markdown;
  md = "# simtree eval: " + result_dir.filename().string() + " against " + capture_dir.string() +
       "/gt\n\n";
  ev.json = {{"format", "simtree.eval_run"},
             {"version", 1},
             {"result", result_dir.string()},
             {"truth", (capture_dir / "gt").string()}};
  ev.json["registration"] = ScoreRegistration(in, md);
  ev.json["reconstruction"] = ScoreReconstruction(in, md);
  ev.json["tracking"] = ScoreTrackingStage(in, md);
  ev.json["identification"] = ScoreIdentification(in, md);
  ev.json["chain"] = ScoreChain(in, options, ev, md);
  return ev;
}

void WriteRunEvaluation(const RunEvaluation& evaluation, const fs::path& out_dir) {
  fs::create_directories(out_dir);
  WriteFileAtomically(out_dir / "eval.json", evaluation.json.dump(1) + "\n");
  WriteFileAtomically(out_dir / "eval.md", evaluation.markdown);
}

}  // namespace simtree::eval
