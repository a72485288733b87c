#pragma once
// `simtree synth`: a whole synthetic capture with its ground truth, the bench every stage is
// scored on (docs/formats.md, "Capture folder"; docs/synth.md).
//
//   1. a procedural tree of a species (tree_generator.h) with red tape markers
//   (marker_placement.h);
//   2. the FEM oracle of that tree (fem_*.h): modes, the pull test's motion, the modal truth;
//   3. the virtual Azure Kinect (sensor_*.h, rgbd_renderer.h): N hand-held static views around the
//      tree, the tree trembling a little between them, then the fixed camera of the pull test
//      (rope tied, pulled, held, cut; the free decay), every frame colour + depth;
//   4. the capture folder (what a real recording gives) and gt/ (what only synth knows), written
//      whole or not at all, plus a contact sheet of every view to look at.
//
// Usage:
//   simtree::synth::SynthOptions options;
//   options.species = "acer_rubrum";
//   options.seed = 7;
//   const simtree::synth::SynthReport report = simtree::synth::RunSynth(options, "scene/");

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "simtree/io/image_io.h"

namespace simtree::synth {

struct SynthOptions {
  std::string species = "acer_rubrum";  // a preset (species.h)
  std::filesystem::path species_file;   // or a custom species JSON (wins over `species`)
  uint64_t seed = 7;
  // A small, fast scene for tests: a smaller tree, 4 views, a 5 s pull stream.
  bool quick = false;
  // More occlusion (a post and a shrub by the tree), more sensor noise, fewer and wider-spaced
  // views; in the pull stream three leaves swinging in front of markers, a red box in view, the
  // light dropping by 0.8 EV after the release and motion blur where markers move fast
  // (docs/synth.md).
  bool hard = false;
  // The pull stream's colour as the renderer makes it, without the camera's pipeline (white
  // balance, auto-exposure drift, sensor noise, defocus, MJPEG; detail/camera_color.h).
  bool clean_color = false;
  // The pull stream's colour camera (`--color-size WxH`): 0 x 0 (default), colour registered to
  // the depth camera's 640 x 576 pixels; an Azure Kinect colour size (1280 x 720, ...), the
  // colour camera of its own beside the depth camera with the depth registered into it, as real
  // recordings are usually processed: the stream's intrinsics, images and ground truth are then
  // the colour camera's (detail/pull_rig.h). The static scans stay registered to depth.
  int color_width = 0;
  int color_height = 0;
  bool HasColorCamera() const { return color_width != 0 || color_height != 0; }
  int views = 0;            // 0: 10 (hard: 7, quick: 4)
  double duration_s = 0.0;  // pull stream length; 0: 15 s (quick: 5 s)
  double fps = 30.0;
  int markers = 12;
  // The rope's pull, as in the paper's Fig. 15: a person pulls a branch well out and lets go, so
  // it and the branches near it swing visibly. The force is chosen so the tied point moves
  // pull_deflection_m at the hold; 0: pull_deflection_per_length times the pulled branch's
  // length (15%: 15-30 cm on the presets' 1-2 m first-level branches; a few cm would leave most
  // links' relative angles at a tracker's noise). Either way the force is capped so no node of
  // the tree turns more than max_pull_rotation_rad at the hold (the FEM is linear: at 0.3 rad sin
  // and tan stay within 1.5% and 3% of the angle, a tip-loaded cantilever's deflection within a
  // few % of the large-deflection one), and kept within [min, max] newtons.
  double pull_deflection_m = 0.0;
  double pull_deflection_per_length = 0.15;
  // Where the rope is tied on the pulled branch, as a share of its length from its base. Near
  // the crotch (35%), where a person ties a rope to pull a branch hard, the pull swings the whole
  // tree and the branches near it, as in the paper's Fig. 15, and on magnolia and acer_rubrum
  // the links' dominant modes fall inside the paper's Table IV (117 of 120 each, seeds 1-10);
  // tied far out (65%, before 2026-11-26) it mostly bends the pulled branch, whose own mode
  // (2-4 Hz on acer_rubrum) then dominates the links on it
  // (docs/synth.md, "Where the rope is tied"). The branch itself is chosen by its outer part
  // (reach, length, taped levels), so the markers and the static scans do not depend on it.
  double pull_position = 0.35;
  double max_pull_rotation_rad = 0.3;
  double min_force_n = 5.0;
  double max_force_n = 400.0;
  // pull/init.json, the tracker's start as a person clicking the markers would give it: each
  // visible marker's tape band centre in the first frame plus a Gaussian error of this standard
  // deviation per axis, px (0: the exact centres).
  double init_click_noise_px = 1.5;
  // Also write contact_sheet.png.
  bool contact_sheet = true;
  // Stop after the FEM oracle: write only gt/ (tree, species, pull load, modal truth, synth.json),
  // no images. Seconds instead of a minute: to check a species' modal truth over many seeds.
  bool truth_only = false;
  PngOptions png;
};

struct SynthReport {
  std::string species;
  uint64_t seed = 0;
  int branches = 0, nodes = 0, levels = 0, markers = 0;
  double height_m = 0.0;
  double first_frequency_hz = 0.0;  // the FEM's lowest mode
  int fem_dof = 0, fem_modes = 0;
  int pull_branch = -1;
  double pull_force_n = 0.0, pull_release_s = 0.0;
  double pull_deflection_m = 0.0;      // of the tied point at the hold
  double pull_max_rotation_rad = 0.0;  // the largest rotation of any node at the hold
  int views = 0, frames = 0;
  // Wall-clock seconds of each part.
  double tree_s = 0, fem_s = 0, scans_s = 0, pull_s = 0, total_s = 0;
  // Valid depth pixels on the tree, mean over the views (how much of it the sensor kept).
  double tree_pixels_per_view = 0.0;

  std::string Summary() const;
};

// Writes the capture to `out` (replaced whole, or left untouched when anything fails). Throws
// InputError for bad options or species, IoError when it cannot write.
SynthReport RunSynth(const SynthOptions& options, const std::filesystem::path& out);

}  // namespace simtree::synth
