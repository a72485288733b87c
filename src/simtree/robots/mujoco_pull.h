#pragma once
// A pull test in MuJoCo on an exported MJCF: a force at one site ramps up (smoothstep, as
// simtree's rope), holds, is let go, and chosen sites are recorded; then the ringing of a site
// (natural frequency and damping ratio of its free decay, read by identify's damped-sinusoid fit).
// This is how the export is checked against the simulation-ready tree it came from.
//
// Usage:
//   simtree::robots::MujocoPullOptions pull;
//   pull.pull_site = "tip_b3";
//   pull.force = {0, 0, -20};
//   pull.record_sites = {"tip_b3", "tip_b0"};
//   const auto run = simtree::robots::RunMujocoPull("tree.xml", pull);
//   const auto ringing = simtree::robots::MeasureRinging(run, 0);

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace simtree::robots {

struct MujocoPullOptions {
  std::string pull_site;                            // the site the force acts at ("tip_b3")
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // at full (N), world
  double hold_s = 1.0;     // full from here (smoothstep ramp from 0 before)
  double release_s = 3.0;  // let go here
  double duration_s = 8.0;
  double sample_hz = 100.0;               // recording rate
  std::vector<std::string> record_sites;  // positions recorded at every sample

  void Validate() const;  // throws OptionError naming the field
};

struct MujocoPullResult {
  std::vector<double> times;                            // s
  std::vector<std::vector<Eigen::Vector3d>> positions;  // [record site][sample], world
  int64_t steps = 0;
  double time_step_s = 0.0;
  double wall_seconds = 0.0;  // stepping only
  double release_s = 0.0;
};

// Loads `mjcf` with MuJoCo and runs the pull. Throws InputError naming the file when MuJoCo
// refuses it, the site when it is not in the model; Error when the simulation goes unstable.
MujocoPullResult RunMujocoPull(const std::filesystem::path& mjcf, const MujocoPullOptions& options);

struct Ringing {
  bool ok = false;
  std::string message;  // why not, when not ok
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double amplitude_m = 0.0;  // of the dominant mode at the start of the decay
};

// The dominant mode of record site `site`'s displacement from its first sample, over the free
// decay from `delay_s` after the release to the end.
Ringing MeasureRinging(const MujocoPullResult& run, int site, double delay_s = 0.05);

}  // namespace simtree::robots
