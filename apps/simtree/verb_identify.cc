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

void RegisterIdentify(CLI::App& app) {
  struct Args {
    std::string input, links, tree, camera_pose, output, plots,
        estimator = ToString(identification::kDefaultEstimator);
    double release_time = -1, window = 0;
    bool no_plots = false, no_compare = false, no_root = false, joint_poles = true;
    double noise_mm = 0, gap_rate = tracking::TrackerErrorOptions{}.gap_start_rate;
    uint64_t seed = 1;
    std::string write_noisy, visibility;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "identify",
      "Natural frequency and damping ratio of every marker link from pull-test trajectories "
      "(paper III-C), with spectra plots and a Table IV-style summary");
  verb->add_option("tracks", args->input,
                   "trajectories.csv, or a folder holding it (what `track` writes)")
      ->required()
      ->check(CLI::ExistingPath);
  verb->add_option("--links", args->links,
                   "markers.json: how markers link (paper Fig. 8); default: markers.json beside "
                   "the trajectories, else from --tree")
      ->check(CLI::ExistingFile);
  verb->add_option("--tree", args->tree,
                   "A static tree (simtree JSON): place each marker on its nearest branch (needs "
                   "--camera-pose), which gives branch ids and, without --links, the links")
      ->check(CLI::ExistingFile);
  verb->add_option("--camera-pose", args->camera_pose,
                   "JSON {\"world_from_camera\": [16 numbers]} of the pull camera (synth writes "
                   "gt/pull_camera.json)")
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output, "materials.json to write")->required();
  verb->add_option("--estimator", args->estimator,
                   "half_power_fft (the paper's), interpolated_spectrum or damped_sinusoid_fit")
      ->capture_default_str()
      ->check(CLI::IsMember({"half_power_fft", "interpolated_spectrum", "damped_sinusoid_fit"}));
  verb->add_flag("--no-compare", args->no_compare, "Run only the chosen estimator");
  verb->add_option("--release-time", args->release_time,
                   "Release time (s, trajectories' clock); default: detected");
  verb->add_option("--window", args->window,
                   "Seconds of free decay to use after the release (0: to the end)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--joint-poles,!--per-link", args->joint_poles,
                 "damped_sinusoid_fit values from poles fitted to all measured links at once "
                 "(they share the tree's modes; each link's own amplitudes pick its dominant "
                 "mode), the default; --per-link fits every link on its own");
  verb->add_flag("--no-root", args->no_root, "Do not estimate the root (trunk) marker's motion");
  verb->add_option("--plots", args->plots,
                   "Folder for one spectra PNG per link (default: <out>_spectra beside --out)");
  verb->add_flag("--no-plots", args->no_plots, "Write no plots");
  auto* testing =
      verb->add_option_group("testing on ground truth",
                             "Feed true positions (synth's gt/trajectories.csv) with errors "
                             "like a tracker's");
  testing
      ->add_option("--simulate-tracker-noise", args->noise_mm,
                   "Add a tracker's errors: this 3D RMS error in mm (twice as large along depth "
                   "as across the image, correlated from frame to frame), short gaps, rare jumps")
      ->check(CLI::NonNegativeNumber);
  testing
      ->add_option("--gap-rate", args->gap_rate,
                   "With --simulate-tracker-noise: chance per marker and frame that a gap starts "
                   "(5 frames long on average)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  testing
      ->add_option("--visibility", args->visibility,
                   "With --simulate-tracker-noise: gt/markers_2d.json; a marker is lost where the "
                   "camera did not see its tape")
      ->check(CLI::ExistingFile);
  testing->add_option("--seed", args->seed, "With --simulate-tracker-noise")->capture_default_str();
  testing->add_option("--write-noisy", args->write_noisy,
                      "Also write the noisy trajectories used (trajectories.csv)");
  verb->footer(Examples({
      "simtree identify tracks/ --links capture/pull/markers.json --out materials.json",
      "simtree identify tracks/trajectories.csv --links markers.json --out m.json --estimator "
      "half_power_fft",
      "simtree identify scene/gt/trajectories.csv --links scene/pull/markers.json --out m.json "
      "--simulate-tracker-noise 2.5 --visibility scene/gt/markers_2d.json --seed 3 --window 10",
      "simtree identify tracks/ --tree static.json --camera-pose scene/gt/pull_camera.json --out "
      "m.json",
  }));
  verb->callback([args] {
    fs::path trajectories_path = args->input;
    if (fs::is_directory(trajectories_path)) trajectories_path /= "trajectories.csv";
    if (!fs::exists(trajectories_path)) {
      throw InputError(args->input, "", "expected trajectories.csv in this folder");
    }
    std::vector<fs::path> inputs = {trajectories_path};
    fs::path links_path = args->links;
    if (links_path.empty() && fs::exists(trajectories_path.parent_path() / "markers.json")) {
      links_path = trajectories_path.parent_path() / "markers.json";
    }
    if (!links_path.empty()) inputs.push_back(links_path);
    if (!args->tree.empty()) inputs.push_back(args->tree);
    if (links_path.empty() && args->tree.empty()) {
      throw InputError(trajectories_path.string(), "",
                       "no marker links: give --links markers.json, or --tree with --camera-pose");
    }
    if (!args->tree.empty() && args->camera_pose.empty()) {
      throw InputError(args->tree, "", "--tree needs --camera-pose (where the pull camera was)");
    }
    RefuseToOverwriteInputs(args->output, inputs);

    Trajectories trajectories = ReadTrajectoriesCsv(trajectories_path);
    if (args->noise_mm > 0) {
      tracking::TrackerErrorOptions noise;
      noise.rms_error_mm = args->noise_mm;
      noise.gap_start_rate = args->gap_rate;
      noise.seed = args->seed;
      std::vector<MarkerFrame2d> visibility;
      if (!args->visibility.empty()) visibility = ReadMarkers2d(args->visibility);
      trajectories = tracking::SimulateTrackerError(
          trajectories, noise, args->visibility.empty() ? nullptr : &visibility);
      spdlog::info("added a tracker's errors: {:.1f} mm RMS, gaps starting at rate {}{}",
                   args->noise_mm, args->gap_rate,
                   args->visibility.empty() ? "" : ", lost where the tape was not seen");
      if (!args->write_noisy.empty()) {
        RefuseToOverwriteInputs(args->write_noisy, inputs);
        WriteTrajectoriesCsv(trajectories, args->write_noisy);
      }
    }
    std::vector<MarkerLink> markers;
    if (!links_path.empty()) markers = ReadMarkersJson(links_path);
    if (!args->tree.empty()) {
      const Tree tree = ReadTreeJson(args->tree);
      const std::vector<identification::MarkerPlacement> placements =
          identification::PlaceMarkersOnTree(tree, trajectories, ReadPullCamera(args->camera_pose));
      if (markers.empty()) {
        markers = identification::LinkMarkersByTree(tree, placements);
        spdlog::info("linked {} markers along the static tree", markers.size());
      } else {
        for (MarkerLink& m : markers) {
          for (const identification::MarkerPlacement& p : placements) {
            if (p.marker == m.id && !m.branch && p.branch >= 0) m.branch = p.branch;
          }
        }
      }
      for (const identification::MarkerPlacement& p : placements) {
        if (p.branch >= 0 && p.distance_m > 0.05) {
          spdlog::warn(
              "marker {} is {:.0f} mm from its nearest branch {}: is the camera pose "
              "right?",
              p.marker, 1e3 * p.distance_m, p.branch);
        }
      }
    }

    identification::IdentifyOptions options;
    options.estimator = *identification::ParseEstimatorKind(args->estimator);
    options.compare_estimators = !args->no_compare;
    if (args->release_time >= 0) options.release_time_s = args->release_time;
    options.window_s = args->window;
    options.include_root = !args->no_root;
    options.joint_poles = args->joint_poles;
    const identification::IdentificationResult result = identification::IdentifyMaterials(
        trajectories, markers, options, trajectories_path.string());
    spdlog::info("release: {}", result.release.note);
    if (!result.joint_poles_note.empty()) spdlog::info("{}", result.joint_poles_note);
    spdlog::info("free decay {:.2f}-{:.2f} s at {:.1f} fps", result.window_start_s,
                 result.window_end_s, result.frame_rate_hz);

    const identification::MaterialsFile materials =
        identification::MaterialsFromIdentification(result, trajectories_path.string());
    if (!args->no_plots) {
      fs::path plots = args->plots;
      if (plots.empty()) {
        const fs::path out(args->output);
        plots = out.parent_path() / (out.stem().string() + "_spectra");
      }
      RefuseToOverwriteInputs(plots, inputs);
      AtomicDirectory folder(plots);
      for (const identification::LinkIdentification& link : result.links) {
        std::string name = link.deflection.link.label;
        for (char& c : name) {
          if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
        }
        identification::WriteLinkPlot(result, link, folder.path() / (name + ".png"));
      }
      folder.Commit();
      spdlog::info("wrote {} spectra plots to {}", result.links.size(), plots.string());
    }
    identification::WriteMaterialsJson(materials, args->output);

    std::printf("%s\n", identification::FormatLinkTable(result).c_str());
    const identification::RangeOptions bounds;
    std::printf(
        "Ranges (paper Table IV), over values known to %.0f%% (frequency) and %.0f%% (damping), "
        "one standard deviation:\n",
        100 * bounds.max_frequency_relative_std, 100 * bounds.max_damping_relative_std);
    std::printf("  %s\n",
                identification::FormatRanges(result.Ranges(), ToString(result.estimator)).c_str());
    for (identification::EstimatorKind kind : identification::AllEstimators()) {
      if (kind == result.estimator || args->no_compare) continue;
      std::printf("  %s\n",
                  identification::FormatRanges(result.Ranges(kind), ToString(kind)).c_str());
    }
    spdlog::info("wrote {} ({} links, {} measured, {} branches)", args->output,
                 materials.links.size(), materials.ranges.measured, materials.branches.size());
  });
}

}  // namespace simtree::cli
