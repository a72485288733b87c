#pragma once
// A few numbers that describe a tree, for `simtree info`, the demo and reports.

#include <string>
#include <vector>

#include "simtree/core/tree.h"

namespace simtree {

struct TreeSummary {
  int branches = 0;
  int nodes = 0;
  int markers = 0;
  std::vector<int> branches_per_level;
  double height_m = 0.0;  // top of the bounds above the trunk base
  double trunk_base_radius_m = 0.0;
  double total_length_m = 0.0;  // sum of branch lengths
  Eigen::Vector3d min_corner = Eigen::Vector3d::Zero(), max_corner = Eigen::Vector3d::Zero();
  // Material ranges over branches that have one (all modes); zero when none.
  int with_material = 0;
  int measured = 0, interpolated = 0, defaulted = 0, assumed = 0;
  int uncertain = 0;  // measured values `build` flagged (Material::uncertain), kept or replaced
  double min_frequency_hz = 0.0, max_frequency_hz = 0.0;
  double min_damping = 0.0, max_damping = 0.0;
};

TreeSummary Summarize(const Tree& tree);
// Human-readable, several lines, no trailing newline.
std::string FormatSummary(const TreeSummary& summary);
// Where the materials came from: "3 measured, 9 interpolated, 0 default" (assumed ones are named
// only when there are some: "12 assumed"; so are uncertain ones: "2 flagged uncertain").
std::string FormatMaterialSources(const TreeSummary& summary);

}  // namespace simtree
