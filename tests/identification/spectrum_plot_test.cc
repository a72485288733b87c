#include "simtree/identification/spectrum_plot.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "simtree/identification/detail/test_signals.h"
#include "test_util.h"

namespace simtree::identification {
namespace {

TEST(SpectrumPlot, OnePngPerLinkIncludingOneThatHasNoSignal) {
  SyntheticMarkerTree tree;
  tree.links.resize(1);
  tree.links[0].theta_u = {{1.2, 0.03, 0.1, 0.0}};
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(tree, 30, 0, 10, &markers);
  markers.push_back({5, "M5", 1, std::nullopt});
  const IdentificationResult r = IdentifyMaterials(t, markers);
  const auto dir = test::TempDir();
  SpectrumPlotOptions options;
  options.width = 800;
  options.height = 600;
  for (size_t i = 0; i < r.links.size(); ++i) {
    const auto path = dir / ("link" + std::to_string(i) + ".png");
    WriteLinkPlot(r, r.links[i], path, options);
    const cv::Mat image = cv::imread(path.string());
    ASSERT_FALSE(image.empty()) << path;
    EXPECT_EQ(image.cols, 800);
    EXPECT_EQ(image.rows, 600);
    // Something was drawn: not all white.
    EXPECT_LT(cv::mean(image)[0], 254.5);
  }
}

}  // namespace
}  // namespace simtree::identification
