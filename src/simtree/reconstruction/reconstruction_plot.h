#pragma once
// A picture for a person to judge a reconstruction: the scan points in grey with the model drawn
// over them (each branch as its silhouette, width 2 r, coloured by level, and its axis), seen
// from the front (x-z) and from the side (y-z) at one scale, with the figures in a caption. PNG.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::reconstruction {

struct ReconstructionPlotOptions {
  int height = 1000;                 // pixels; the width follows from the two views
  double model_opacity = 0.55;       // of the branch silhouettes over the points
  int point_size = 1;                // pixels per point (larger for sparse clouds)
  std::vector<std::string> caption;  // lines printed under the title
  std::string title;                 // printed at the top

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

// Writes `path` atomically. Throws IoError when it cannot be written, OptionError for invalid
// options.
void WriteReconstructionPlot(const Tree& tree, std::span<const Eigen::Vector3d> points,
                             const std::filesystem::path& path,
                             const ReconstructionPlotOptions& options = {});

}  // namespace simtree::reconstruction
