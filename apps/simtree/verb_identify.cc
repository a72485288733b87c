#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/identification/identify.h"
#include "simtree/identification/marker_assignment.h"
#include "simtree/identification/materials_file.h"
#include "simtree/identification/spectrum_plot.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"
#include "simtree/tracking/tracker_error.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

struct IdentifyArgs {
  std::string input, links, tree, camera_pose, output, plots,
      estimator = ToString(identification::kDefaultEstimator);
  double release_time = -1, window = 0;
  bool no_plots = false, no_compare = false, no_root = false, joint_poles = false, per_link = false;
  double noise_mm = 0, gap_rate = tracking::TrackerErrorOptions{}.gap_start_rate;
  uint64_t seed = 1;
  std::string write_noisy, visibility;
};

void AddIdentifyOptions(CLI::App* verb, IdentifyArgs& a) {
  verb->add_option("tracks", a.input,
                   "trajectories.csv, or a folder holding it (what `track` writes)")
      ->required()
      ->check(CLI::ExistingPath);
  verb->add_option("--links", a.links,
                   "markers.json: how markers link (paper Fig. 8); default: markers.json beside "
                   "the trajectories, else from --tree")
      ->check(CLI::ExistingFile);
  verb->add_option("--tree", a.tree,
                   "A static tree (simtree JSON): place each marker on its nearest branch (needs "
                   "--camera-pose), which gives branch ids and, without --links, the links")
      ->check(CLI::ExistingFile);
  verb->add_option("--camera-pose", a.camera_pose,
                   "JSON {\"world_from_camera\": [16 numbers]} of the pull camera (synth writes "
                   "gt/pull_camera.json)")
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", a.output, "materials.json to write")->required();
  verb->add_option("--estimator", a.estimator,
                   "half_power_fft (the paper's), interpolated_spectrum or damped_sinusoid_fit")
      ->capture_default_str()
      ->check(CLI::IsMember({"half_power_fft", "interpolated_spectrum", "damped_sinusoid_fit"}));
  verb->add_flag("--no-compare", a.no_compare, "Run only the chosen estimator");
  verb->add_option("--release-time", a.release_time,
                   "Release time (s, trajectories' clock); default: detected");
  verb->add_option("--window", a.window,
                   "Seconds of free decay to use after the release (0: to the end)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  auto* joint = verb->add_flag(
      "--joint-poles", a.joint_poles,
      "damped_sinusoid_fit values of every link from the poles fitted to all measured links at "
      "once (the tree's shared modes). Default: each link reads the shared poles only when its "
      "record supports them (BIC against its own fit; materials.json links[].poles says which)");
  verb->add_flag("--per-link", a.per_link,
                 "damped_sinusoid_fit values of every link from its own fit alone")
      ->excludes(joint);
  verb->add_flag("--no-root", a.no_root, "Do not estimate the root (trunk) marker's motion");
  verb->add_option("--plots", a.plots,
                   "Folder for one spectra PNG per link (default: <out>_spectra beside --out)");
  verb->add_flag("--no-plots", a.no_plots, "Write no plots");
}

void AddTestingOptions(CLI::App* verb, IdentifyArgs& a) {
  auto* testing =
      verb->add_option_group("testing on ground truth",
                             "Feed true positions (synth's gt/trajectories.csv) with errors "
                             "like a tracker's");
  testing
      ->add_option("--simulate-tracker-noise", a.noise_mm,
                   "Add a tracker's errors: this 3D RMS error in mm (twice as large along depth "
                   "as across the image, correlated from frame to frame), short gaps, rare jumps")
      ->check(CLI::NonNegativeNumber);
  testing
      ->add_option("--gap-rate", a.gap_rate,
                   "With --simulate-tracker-noise: chance per marker and frame that a gap starts "
                   "(5 frames long on average)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  testing
      ->add_option("--visibility", a.visibility,
                   "With --simulate-tracker-noise: gt/markers_2d.json; a marker is lost where the "
                   "camera did not see its tape")
      ->check(CLI::ExistingFile);
  testing->add_option("--seed", a.seed, "With --simulate-tracker-noise")->capture_default_str();
  testing->add_option("--write-noisy", a.write_noisy,
                      "Also write the noisy trajectories used (trajectories.csv)");
}

// The files the verb reads: the trajectories (a folder means its trajectories.csv) and the marker
// links (markers.json beside them unless given).
struct IdentifyInputs {
  fs::path trajectories, links;
  std::vector<fs::path> all;  // every input, which no output may overwrite
};

IdentifyInputs ResolveInputs(const IdentifyArgs& a) {
  IdentifyInputs in;
  in.trajectories = a.input;
  if (fs::is_directory(in.trajectories)) in.trajectories /= "trajectories.csv";
  if (!fs::exists(in.trajectories)) {
    throw InputError(a.input, "", "expected trajectories.csv in this folder");
  }
  in.all = {in.trajectories};
  in.links = a.links;
  if (in.links.empty() && fs::exists(in.trajectories.parent_path() / "markers.json")) {
    in.links = in.trajectories.parent_path() / "markers.json";
  }
  if (!in.links.empty()) in.all.push_back(in.links);
  if (!a.tree.empty()) in.all.push_back(a.tree);
  if (in.links.empty() && a.tree.empty()) {
    throw InputError(in.trajectories.string(), "",
                     "no marker links: give --links markers.json, or --tree with --camera-pose");
  }
  if (!a.tree.empty() && a.camera_pose.empty()) {
    throw InputError(a.tree, "", "--tree needs --camera-pose (where the pull camera was)");
  }
  RefuseToOverwriteInputs(a.output, in.all);
  return in;
}

// --simulate-tracker-noise: the true tracks with a tracker's errors.
Trajectories AddTrackerErrors(Trajectories trajectories, const IdentifyArgs& a,
                              const IdentifyInputs& in) {
  tracking::TrackerErrorOptions noise;
  noise.rms_error_mm = a.noise_mm;
  noise.gap_start_rate = a.gap_rate;
  noise.seed = a.seed;
  std::vector<MarkerFrame2d> visibility;
  if (!a.visibility.empty()) visibility = ReadMarkers2d(a.visibility);
  trajectories = tracking::SimulateTrackerError(trajectories, noise,
                                                a.visibility.empty() ? nullptr : &visibility);
  spdlog::info("added a tracker's errors: {:.1f} mm RMS, gaps starting at rate {}{}", a.noise_mm,
               a.gap_rate, a.visibility.empty() ? "" : ", lost where the tape was not seen");
  if (!a.write_noisy.empty()) {
    RefuseToOverwriteInputs(a.write_noisy, in.all);
    WriteTrajectoriesCsv(trajectories, a.write_noisy);
  }
  return trajectories;
}

void RunIdentify(const IdentifyArgs& a) {
  const IdentifyInputs in = ResolveInputs(a);
  Trajectories trajectories = ReadTrajectoriesCsv(in.trajectories);
  if (a.noise_mm > 0) trajectories = AddTrackerErrors(std::move(trajectories), a, in);
  std::vector<MarkerLink> markers;
  if (!in.links.empty()) markers = ReadMarkersJson(in.links);
  if (!a.tree.empty()) {
    markers = identification::MarkersOnTree(ReadTreeJson(a.tree), trajectories,
                                            ReadPullCamera(a.camera_pose), std::move(markers))
                  .markers;
  }

  identification::IdentifyOptions options;
  options.estimator = *identification::ParseEstimatorKind(a.estimator);
  options.compare_estimators = !a.no_compare;
  if (a.release_time >= 0) options.release_time_s = a.release_time;
  options.window_s = a.window;
  options.include_root = !a.no_root;
  options.joint_poles = !a.per_link;
  options.choose_per_link = !a.joint_poles;
  const identification::IdentificationResult result =
      identification::IdentifyMaterials(trajectories, markers, options, in.trajectories.string());
  spdlog::info("release: {}", result.release.note);
  if (!result.joint_poles_note.empty()) spdlog::info("{}", result.joint_poles_note);
  spdlog::info("free decay {:.2f}-{:.2f} s at {:.1f} fps", result.window_start_s,
               result.window_end_s, result.frame_rate_hz);

  const identification::MaterialsFile materials =
      identification::MaterialsFromIdentification(result, in.trajectories.string());
  if (!a.no_plots) {
    fs::path plots = a.plots;
    if (plots.empty()) {
      const fs::path out(a.output);
      plots = out.parent_path() / (out.stem().string() + "_spectra");
    }
    RefuseToOverwriteInputs(plots, in.all);
    identification::WriteLinkPlots(result, plots);
    spdlog::info("wrote {} spectra plots to {}", result.links.size(), plots.string());
  }
  identification::WriteMaterialsJson(materials, a.output);
  std::printf("%s", identification::FormatSummary(result).c_str());
  spdlog::info("wrote {} ({} links, {} measured, {} branches)", a.output, materials.links.size(),
               materials.ranges.measured, materials.branches.size());
}

}  // namespace

void RegisterIdentify(CLI::App& app) {
  auto args = std::make_shared<IdentifyArgs>();
  CLI::App* verb = app.add_subcommand(
      "identify",
      "Natural frequency and damping ratio of every marker link from pull-test trajectories "
      "(paper III-C), with spectra plots and a Table IV-style summary");
  AddIdentifyOptions(verb, *args);
  AddTestingOptions(verb, *args);
  verb->footer(Examples({
      "simtree identify tracks/ --links capture/pull/markers.json --out materials.json",
      "simtree identify tracks/trajectories.csv --links markers.json --out m.json --estimator "
      "half_power_fft",
      "simtree identify scene/gt/trajectories.csv --links scene/pull/markers.json --out m.json "
      "--simulate-tracker-noise 2.5 --visibility scene/gt/markers_2d.json --seed 3 --window 10",
      "simtree identify tracks/ --tree static.json --camera-pose scene/gt/pull_camera.json --out "
      "m.json",
  }));
  verb->callback([args] { RunIdentify(*args); });
}

}  // namespace simtree::cli
