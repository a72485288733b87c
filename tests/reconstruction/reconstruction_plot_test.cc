#include "simtree/reconstruction/reconstruction_plot.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/io/image_io.h"
#include "simtree/reconstruction/detail/allometric_radii.h"
#include "simtree/reconstruction/detail/branch_decomposition.h"
#include "test_util.h"

namespace simtree::reconstruction {
namespace {

TEST(ReconstructionPlot, DrawsTheModelOverThePoints) {
  Skeleton y = test::YSkeleton();
  AssignRadii(y, 0, 0.05, 0.0, {}, 0.0, {.local_fits = false});
  const Tree tree = DecomposeIntoBranches(y);
  const auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 1.0, 0.05, 0.01);
  const auto path = test::TempDir() / "plot.png";
  ReconstructionPlotOptions options;
  options.height = 600;
  options.title = "test";
  WriteReconstructionPlot(tree, points, path, options);
  const RgbImage image = ReadColorImage(path);
  EXPECT_EQ(image.height, 600);
  EXPECT_GE(image.width, 640);
  // Some pixels carry the trunk's colour (brown: red above blue) and some the points' grey.
  int brown = 0, grey = 0;
  for (int y0 = 0; y0 < image.height; ++y0) {
    for (int x = 0; x < image.width; ++x) {
      const int r = image.at(x, y0, 0), g = image.at(x, y0, 1), b = image.at(x, y0, 2);
      brown += r > b + 30 && r < 230;
      grey += r == 140 && g == 140 && b == 140;
    }
  }
  EXPECT_GT(brown, 100);
  EXPECT_GT(grey, 10);
}

TEST(ReconstructionPlot, AnEmptyTreeStillDrawsThePoints) {
  const auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 1.0, 0.05, 0.01);
  const auto path = test::TempDir() / "points.png";
  WriteReconstructionPlot(Tree{}, points, path);
  EXPECT_FALSE(ReadColorImage(path).empty());
}

}  // namespace
}  // namespace simtree::reconstruction
