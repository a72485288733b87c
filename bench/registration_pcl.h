#pragma once
// F-4PCS-ICP with PCL (paper Table II): PCL's FPCSInitialAlignment, then PCL's ICP. PCL is linked
// only by bench/ (NOTES.md: its CMake config fails on Debian 12; pkg-config works).

#include "simtree/registration/baselines.h"

namespace simtree::bench {

struct FpcsOptions {
  double approx_overlap = 0.5;
  double delta_factor = 2.0;  // FPCS's delta in point spacings
  int samples = 200;
  double max_seconds = 5.0;
  int threads = 2;
};

registration::BaselineResult Fpcs4PcsIcp(const open3d::geometry::PointCloud& source,
                                         const open3d::geometry::PointCloud& target,
                                         const registration::BaselineOptions& options,
                                         const FpcsOptions& fpcs = {});

}  // namespace simtree::bench
