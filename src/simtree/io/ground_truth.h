#pragma once
// The gt/ folder of a synthetic capture (docs/formats.md, "Capture folder"): what `synth` knows and
// the pipeline must find out. Written only by synth; read by eval, benchmarks and tests, never by a
// stage.
//
//   gt/tree.json            the true rest tree with its markers (core/tree_json.h)
//   gt/scan_poses.json      world_from_camera of every scan view
//   gt/pull_camera.json     world_from_camera of the pull-test camera
//   gt/pull_load.json       the rope pull: branch, arc length, anchor, force, times
//   gt/trajectories.csv     true marker centres per pull frame (simtree.trajectories)
//   gt/markers_2d.json      per frame and marker: visible, box [x, y, w, h] in pixels
//   gt/modal.json           FEM modal truth: tree modes, per marker link, per branch

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "simtree/core/json_util.h"

namespace simtree {

// A rigid transform as JSON: 16 numbers, row-major, last row 0 0 0 1, rotation orthonormal
// (within 1e-6).
Eigen::Isometry3d PoseFromJson(const JsonNode& value);
nlohmann::ordered_json PoseToJson(const Eigen::Isometry3d& pose);

struct ViewPose {
  std::string name;  // the view folder, "view_00"
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
};
std::vector<ViewPose> ReadScanPoses(const std::filesystem::path& path);
void WriteScanPoses(const std::vector<ViewPose>& poses, const std::filesystem::path& path);

Eigen::Isometry3d ReadPullCamera(const std::filesystem::path& path);
void WritePullCamera(const Eigen::Isometry3d& world_from_camera, const std::filesystem::path& path);

// The pull test: a rope tied to `branch` at `arc_length` (its rest point `attach_point`), pulled
// towards `anchor` with a force that ramps from 0 at `ramp_start_s` to `force_n` at
// `hold_start_s`, is held, and is cut (released at once) at `release_s`. World frame.
struct PullLoad {
  int branch = 0;
  double arc_length = 0.0;  // metres from the branch base
  Eigen::Vector3d attach_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  double force_n = 0.0;
  double ramp_start_s = 0.0;
  double hold_start_s = 0.0;
  double release_s = 0.0;
  double duration_s = 0.0;  // length of the recorded stream
  // Force (N) along (anchor - attach_point) at time t.
  double ForceAt(double t) const;
  Eigen::Vector3d Direction() const { return (anchor - attach_point).normalized(); }
};
PullLoad ReadPullLoad(const std::filesystem::path& path);
void WritePullLoad(const PullLoad& load, const std::filesystem::path& path);

// One marker in one frame of the pull stream. `box` is the projection of the whole tape band
// (x, y of the top-left corner, width, height, pixels), clipped to the image; all zero when the
// band is entirely outside it. `visible_fraction` is the share of the band's unoccluded pixels
// that the camera sees; `visible` is what a tracker should be held to (enough of the tape shows).
struct MarkerBox2d {
  int id = 0;
  bool visible = false;
  double visible_fraction = 0.0;
  int visible_pixels = 0;
  std::array<double, 4> box = {0, 0, 0, 0};
};
struct MarkerFrame2d {
  int frame = 0;
  double time_s = 0.0;
  std::vector<MarkerBox2d> markers;  // every marker, in markers.json order
};
std::vector<MarkerFrame2d> ReadMarkers2d(const std::filesystem::path& path);
void WriteMarkers2d(const std::vector<MarkerFrame2d>& frames, const std::filesystem::path& path);

// The FEM oracle's modal truth (definitions in synth/fem_truth.h).
struct ModalTruth {
  struct TreeMode {
    double frequency_hz = 0.0;
    double damping_ratio = 0.0;
    // Effective-mass fractions (synth/fem_effective_mass.h): the share of the horizontal mass
    // (x and y summed) and of the polar moment about the vertical through the trunk base the
    // mode carries. Optional in the file (older files have neither).
    std::optional<double> horizontal_mass_fraction = std::nullopt;
    std::optional<double> torsion_mass_fraction = std::nullopt;
  };
  // One mode's share of a deflection signal after release (optional in the file: "peaks").
  struct ModePeak {
    int mode = 0;  // index into `modes`
    double frequency_hz = 0.0;
    double damping_ratio = 0.0;
    // The mode's amplitude in the signal at release (rad; metres for the root marker).
    double amplitude = 0.0;
    // Its spectral peak over the record T after release: amplitude (1 - e^(-zeta w T)) / (zeta w).
    double strength = 0.0;
  };
  // The dominant mode of a marker link's relative deflection (paper Fig. 8b); parent -1 is the
  // root marker's own displacement.
  struct Link {
    int parent = -1;  // marker ids
    int child = 0;
    double frequency_hz = 0.0;
    double damping_ratio = 0.0;
    std::vector<ModePeak> peaks = {};  // strongest first (the dominant mode, then the runner-up)
  };
  // The dominant mode of a branch's own deflection relative to its parent.
  struct BranchTruth {
    int branch = 0;
    double frequency_hz = 0.0;
    double damping_ratio = 0.0;
    std::vector<ModePeak> peaks = {};  // strongest first
  };
  std::string source;           // what produced it ("fem", or "stand-in" while the FEM is not in)
  std::vector<TreeMode> modes;  // ascending frequency
  // The lowest sway mode (index into `modes`; synth/fem_effective_mass.h's LowestSwayMode).
  // Optional in the file (older files do not have it; absent too when no mode sways).
  std::optional<int> lowest_sway_mode = std::nullopt;
  std::vector<Link> links;
  std::vector<BranchTruth> branches;
};
ModalTruth ReadModalTruth(const std::filesystem::path& path);
void WriteModalTruth(const ModalTruth& truth, const std::filesystem::path& path);

}  // namespace simtree
