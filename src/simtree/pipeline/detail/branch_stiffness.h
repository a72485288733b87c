#pragma once
// The pull test also measures how stiff the branches are against the trunk. Identification reads
// each marker link's strongest ringing, which on a tree with a coupled crown is the whole tree's
// sway, so `build` gives every measured branch about that one frequency: branches as limp as the
// trunk is stiff, which bend under the rope where the real ones carry it to the trunk. Here the
// branches above the trunk are made stiffer by one factor on their modal frequencies (stiffness
// by its square, masses kept), and the factor whose tree best replays the tracked pull (the pull
// fit's motion residual, pull_motion_fit.h) is kept: the data choose, no truth is read.

#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/pull_fit.h"

namespace simtree::pipeline::detail {

struct StiffnessCalibrationOptions {
  // Frequency factors tried on every branch above the trunk (each >= 1, increasing; 1 is the
  // identified tree itself). A factor f makes a branch f^2 times stiffer.
  std::vector<double> factors = {1.0, 1.41, 2.0, 2.83, 4.0, 5.66, 8.0};
  // The smallest factor whose replay residual is within this share of the best one wins, so a
  // flat optimum does not push the branches stiffer than the data ask (>= 0).
  double tolerance = 0.02;

  // Throws InputError ("stiffness calibration options", the field) for a value out of range.
  void Validate() const;
};

struct StiffnessTrial {
  double factor = 1.0;
  double residual_rms_m = 0.0;  // the pull fit's motion residual (held pose when no motion fit)
};

struct StiffnessCalibration {
  double factor = 1.0;  // the chosen frequency factor for the branches above the trunk
  std::vector<StiffnessTrial> trials;
  PullFit fit;  // the pull fitted on the chosen tree
};

// `tree` with every branch of level >= 1 made `factor` times higher in modal frequency.
Tree StiffenBranches(const Tree& tree, double factor);

// Fits the pull (FitPull, the same arguments) on the tree stiffened by each factor and keeps the
// best. Throws as FitPull does when no factor's tree can be fitted.
StiffnessCalibration CalibrateBranchStiffness(const Tree& tree, const Trajectories& tracks,
                                              const Eigen::Isometry3d& world_from_camera,
                                              double release_s, const std::vector<int>& excluded,
                                              const PullFitOptions& fit_options,
                                              const StiffnessCalibrationOptions& options = {});

}  // namespace simtree::pipeline::detail
