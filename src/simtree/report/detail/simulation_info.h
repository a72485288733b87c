#pragma once
// simulate/simulation.json, what the report needs of it: the frame rate, the pull's times and
// rope, and the tree file that was simulated. Read leniently: any member may be missing.

#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "simtree/report/detail/result_folder.h"

namespace simtree::report {

struct SimulationInfo {
  double fps = 30.0;
  double duration_s = 0.0;
  std::string tree;  // as written
  struct Pull {
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), anchor = Eigen::Vector3d::Zero();
    double hold_s = 0.0, release_s = 0.0, tension_n = 0.0;
    int branch = -1;
  };
  std::optional<Pull> pull;
  bool wind = false;
  std::string integrator;
};

// simulate/simulation.json of the folder, or nothing when it is missing or does not read.
std::optional<SimulationInfo> ReadSimulationInfo(const ResultFolder& folder);

}  // namespace simtree::report
