#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/synth/species.h"
#include "simtree/synth/synth.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

namespace {

// "1280x720" -> (1280, 720); which sizes are the camera's, synth checks.
std::pair<int, int> ParseColorSize(const std::string& text) {
  int width = 0, height = 0;
  char separator = 0;
  std::istringstream in(text);
  if (!(in >> width >> separator >> height) || (separator != 'x' && separator != 'X') ||
      !in.eof() || width <= 0 || height <= 0) {
    throw InputError("synth", "--color-size",
                     fmt::format("expected WIDTHxHEIGHT such as 1280x720, got \"{}\"", text));
  }
  return {width, height};
}

}  // namespace

void RegisterSynth(CLI::App& app) {
  struct Args {
    synth::SynthOptions synth;
    std::string output, species_file;
    std::string color_size = "640x576";
    bool list_species = false, no_sheet = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "synth",
      "Make a synthetic capture with ground truth: a procedural leafless tree with tape "
      "markers, its whole-tree FEM motion, multi-view RGB-D scans and a pull-test RGB-D stream "
      "from a virtual Azure Kinect, and gt/ (true tree, poses, marker tracks, modal truth)");
  verb->add_option("-o,--out", args->output,
                   "Capture folder to write (replaced whole, or left untouched on error)");
  std::string presets;
  for (const std::string& name : synth::SpeciesPresetNames()) {
    presets += (presets.empty() ? "" : ", ") + name;
  }
  verb->add_option("--species", args->synth.species, "Species preset: " + presets)
      ->capture_default_str();
  verb->add_option("--species-file", args->species_file,
                   "A custom species JSON (see docs/synth.md; \"base\": a preset to start from)")
      ->check(CLI::ExistingFile);
  verb->add_option("--seed", args->synth.seed, "Random seed: same seed, same bytes")
      ->capture_default_str();
  verb->add_flag("--quick", args->synth.quick,
                 "A small fast scene for tests: smaller tree, 4 views, 5 s stream");
  verb->add_flag("--hard", args->synth.hard,
                 "Harder: a post and a shrub by the tree, more sensor noise, 7 views with wider "
                 "and uneven gaps; in the pull stream leaves swinging in front of markers, a red "
                 "box in view, a drop of the light and motion blur at the swing's fastest");
  verb->add_flag("--clean-color", args->synth.clean_color,
                 "The pull stream's colour as rendered. Default: as a real camera delivers it "
                 "(white balance a little off, auto-exposure drifting, sensor noise, slight "
                 "defocus, MJPEG compression; --hard adds an exposure change)");
  verb->add_option("--color-size", args->color_size,
                   "The pull stream's colour camera, WxH: 640x576 (default) colour registered to "
                   "the depth camera's pixels; an Azure Kinect colour size (1280x720, 1920x1080, "
                   "2560x1440, 3840x2160, 2048x1536, 4096x3072) renders the colour camera beside "
                   "the depth camera and registers depth into it, as real recordings are usually "
                   "processed; the stream's intrinsics and gt/ are then the colour camera's")
      ->capture_default_str();
  verb->add_option("--views", args->synth.views, "Static views (default 10; hard 7; quick 4)")
      ->check(CLI::Range(1, 72));
  verb->add_option("--duration", args->synth.duration_s,
                   "Pull stream length in seconds (default 15; quick 5)")
      ->check(CLI::Range(0.5, 600.0));
  verb->add_option("--fps", args->synth.fps, "Pull stream frame rate")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 120.0));
  verb->add_option("--markers", args->synth.markers, "Tape markers on the tree (every level)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  verb->add_option("--pull-deflection", args->synth.pull_deflection_m,
                   "How far the rope moves the tied point at the hold (m); the force follows. "
                   "0 (default): 15% of the pulled branch's length, less if any part of the "
                   "tree would turn more than 0.3 rad (the FEM is linear)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.9));
  verb->add_option("--pull-position", args->synth.pull_position,
                   "Where the rope is tied, as a share of the pulled branch's length from its "
                   "base: near the crotch (default) the whole tree swings, as in the paper's pull "
                   "tests; far out (0.65) mostly the pulled branch, at its own higher mode")
      ->capture_default_str()
      ->check(CLI::Range(0.05, 0.95));
  verb->add_option("--init-noise", args->synth.init_click_noise_px,
                   "pull/init.json (the tracker's start) holds each visible marker's first-frame "
                   "pixel as a person clicking it gives it: the tape band's centre plus a seeded "
                   "Gaussian error of this standard deviation per axis (px; 0: exact)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 50.0));
  verb->add_flag("--no-contact-sheet", args->no_sheet, "Do not write contact_sheet.png");
  verb->add_flag("--truth-only", args->synth.truth_only,
                 "Only the tree and its FEM truth: gt/ with tree, species, pull load and modal "
                 "truth, no images (seconds; to check a species over many seeds)");
  verb->add_flag("--list-species", args->list_species,
                 "Print the species presets and what each is modelled on, then exit");
  verb->footer(Examples({
      "simtree synth --species acer_rubrum --seed 7 --out scene/",
      "simtree synth --quick --out /tmp/quick_scene",
      "simtree synth --species magnolia --seed 3 --hard --out hard_scene/",
      "simtree synth --species magnolia --seed 1 --color-size 1280x720 --out hd_scene/",
      "simtree synth --species-file my_species.json --seed 1 --out custom/",
      "simtree synth --list-species",
  }));
  verb->callback([args] {
    if (args->list_species) {
      for (const std::string& name : synth::SpeciesPresetNames()) {
        std::printf("%-14s %s\n", name.c_str(), synth::SpeciesPreset(name).description.c_str());
      }
      return;
    }
    if (args->output.empty()) throw InputError("synth", "--out", "expected an output folder");
    synth::SynthOptions options = args->synth;
    options.species_file = args->species_file;
    options.contact_sheet = !args->no_sheet;
    const std::pair<int, int> color_size = ParseColorSize(args->color_size);
    if (color_size != std::pair{640, 576}) {
      options.color_width = color_size.first;
      options.color_height = color_size.second;
    }
    if (!args->species_file.empty()) RefuseToOverwriteInputs(args->output, {args->species_file});
    const synth::SynthReport report = synth::RunSynth(options, args->output);
    spdlog::info("synth: {}", report.Summary());
    if (options.truth_only) {
      std::printf("wrote %s: gt/ (tree, species, pull load, modal truth)\n", args->output.c_str());
      return;
    }
    std::printf(
        "wrote %s: %d views, %d pull frames, gt/ (tree, poses, marker tracks, modal "
        "truth)%s\n",
        args->output.c_str(), report.views, report.frames,
        options.contact_sheet ? "; look at contact_sheet.png" : "");
  });
}

}  // namespace simtree::cli
