// The pull camera placed in the registration frame (RegisterPullFrame), against the truth of
// synthetic captures: the captures' views registered as `simtree register` does, the pull
// stream's first frame registered to them like one more view, and its pose relative to a scan
// view (view_00, else the anchor) compared with the true one (gt/scan_poses.json,
// gt/pull_camera.json). The library never reads gt/; this program does, to score it.
//
//   registration_pull_camera --species acer_palmatum magnolia acer_rubrum --seeds 3
//   registration_pull_camera --markdown t.md --json p.json
//   registration_pull_camera --captures scene1/ scene2/

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <open3d/utility/Logging.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "simtree/core/tree_json.h"
#include "simtree/eval/registration_metrics.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/register.h"
#include "simtree/registration/register_extra_view.h"
#include "synth_capture_set.h"

namespace fs = std::filesystem;
using namespace simtree;

namespace {

// One capture's outcome.
struct Outcome {
  std::string capture;
  int views_registered = 0, views = 0;
  std::string reference;  // the scan view the pose is compared against
  registration::ExtraViewResult pull;
  double rotation_error_deg = NAN;  // of reference_from_pull
  double position_error_m = NAN;    // the pull camera's position in the reference view's frame
  double tree_rms_m = NAN;          // the tree points the pull camera sees, displaced
  double seconds = 0.0;             // preprocessing, views registered, pull frame registered
};

// The estimated pose against the truth, relative to a registered scan view.
void Score(const fs::path& root, const registration::MultiViewResult& result, Outcome& o) {
  const std::vector<ViewPose> truth = ReadScanPoses(root / "gt" / "scan_poses.json");
  const Eigen::Isometry3d world_from_pull = ReadPullCamera(root / "gt" / "pull_camera.json");
  int reference = result.anchor;
  for (size_t v = 0; v < result.views.size(); ++v) {
    if (result.views[v].name == "view_00" && result.views[v].registered()) {
      reference = static_cast<int>(v);
    }
  }
  o.reference = result.views[reference].name;
  const auto it = std::find_if(truth.begin(), truth.end(),
                               [&](const ViewPose& p) { return p.name == o.reference; });
  if (it == truth.end() || !o.pull.placed()) return;
  const Eigen::Isometry3d estimated =
      result.views[reference].frame_from_camera.inverse() * o.pull.frame_from_camera;
  const Eigen::Isometry3d true_pose = it->world_from_camera.inverse() * world_from_pull;
  o.rotation_error_deg = Eigen::AngleAxisd((true_pose.inverse() * estimated).linear()).angle() *
                         180.0 / std::numbers::pi;
  o.position_error_m = (estimated.translation() - true_pose.translation()).norm();
  o.tree_rms_m =
      eval::ViewPoseError(o.pull.frame_from_camera, result.views[reference].frame_from_camera,
                          world_from_pull, it->world_from_camera,
                          eval::TreeSamplePoints(ReadTreeJson(root / "gt" / "tree.json")))
          .tree_rms_m;
}

Outcome RunCapture(const fs::path& root, const std::string& label) {
  fmt::print(stderr, "{}\n", label);
  const auto start = std::chrono::steady_clock::now();
  Outcome o;
  o.capture = label;
  // The options as `simtree register` takes them by default (named: GCC 12 misreads temporaries).
  const preprocessing::PreprocessOptions preprocess;
  const registration::RegistrationViewOptions view_options;
  const registration::MultiViewOptions options;
  const registration::ExtraViewOptions pull_options;
  const Capture capture = OpenCapture(root);
  const std::vector<registration::RegistrationView> views = registration::PrepareViews(
      preprocessing::PreprocessCaptureViews(capture, preprocess), view_options);
  const registration::MultiViewResult result = registration::RegisterViews(views, options);
  o.views = static_cast<int>(result.views.size());
  o.views_registered = result.RegisteredCount();
  o.pull = registration::RegisterPullFrame(capture, views, result, preprocess, view_options,
                                           pull_options);
  o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Score(root, result, o);
  return o;
}

std::string Markdown(const std::vector<Outcome>& outcomes) {
  std::string md =
      "| capture | views registered | pull camera | pairs used | rotation error (deg) | camera "
      "position error (mm) | tree RMS (mm) | spread (deg / mm) | time: views, pull (s) |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::vector<double> rotation, position, tree;
  for (const Outcome& o : outcomes) {
    md += fmt::format(
        "| {} | {} of {} | {} | {} of {} | {:.2f} | {:.0f} | {:.1f} | {:.2f} / {:.0f} | {:.0f}, "
        "{:.0f} "
        "|\n",
        o.capture, o.views_registered, o.views, o.pull.status, o.pull.pairs_used,
        o.pull.pairs.size(), o.rotation_error_deg, 1e3 * o.position_error_m, 1e3 * o.tree_rms_m,
        o.pull.rotation_spread_deg, 1e3 * o.pull.shift_spread_m, o.seconds - o.pull.seconds,
        o.pull.seconds);
    if (!o.pull.placed()) continue;
    rotation.push_back(o.rotation_error_deg);
    position.push_back(1e3 * o.position_error_m);
    tree.push_back(1e3 * o.tree_rms_m);
  }
  md += fmt::format(
      "\nPlaced: {} of {}. Rotation error median {:.2f} deg, largest {:.2f}; camera position "
      "{:.0f} mm, largest {:.0f}; tree RMS {:.1f} mm, largest {:.1f}.\n",
      rotation.size(), outcomes.size(), bench::Median(rotation), bench::Largest(rotation),
      bench::Median(position), bench::Largest(position), bench::Median(tree), bench::Largest(tree));
  return md;
}

nlohmann::ordered_json Json(const std::vector<Outcome>& outcomes) {
  nlohmann::ordered_json doc = nlohmann::ordered_json::array();
  for (const Outcome& o : outcomes) {
    doc.push_back({{"capture", o.capture},
                   {"views_registered", o.views_registered},
                   {"views", o.views},
                   {"reference", o.reference},
                   {"outcome", ToString(o.pull.outcome)},
                   {"status", o.pull.status},
                   {"pairs_used", o.pull.pairs_used},
                   {"rotation_error_deg", o.rotation_error_deg},
                   {"position_error_mm", 1e3 * o.position_error_m},
                   {"tree_rms_mm", 1e3 * o.tree_rms_m},
                   {"rotation_spread_deg", o.pull.rotation_spread_deg},
                   {"shift_spread_mm", 1e3 * o.pull.shift_spread_m},
                   {"view_overlap", o.pull.view_overlap},
                   {"seconds", o.seconds},
                   {"pull_seconds", o.pull.seconds}});
  }
  return doc;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The pull camera in the registration frame, against the truth of synth captures"};
  bench::CaptureSetArgs args;
  args.seeds = 3;
  args.AddOptions(app);
  CLI11_PARSE(app, argc, argv);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);

  std::vector<Outcome> outcomes;
  for (const bench::CaptureEntry& capture : bench::ResolveCaptures(args)) {
    outcomes.push_back(RunCapture(capture.root, capture.label));
  }
  bench::WriteOutputs(args, Markdown(outcomes), Json(outcomes));
  return 0;
}
