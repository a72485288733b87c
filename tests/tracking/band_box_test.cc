// The tracker's boxes come from each marker's band model: whole in frames where a twig hides part
// of the tape.
#include <gtest/gtest.h>

#include "drawn_stream.h"
#include "simtree/eval/tracking_metrics.h"
#include "simtree/tracking/detail/marker_tracker.h"

namespace simtree::tracking::detail {
namespace {

TEST(MarkerTrackerBox, APartlyHiddenTapeKeepsItsWholeBandsBox) {
  test::DrawnStream s;
  const Eigen::Vector3d start(0.01, -0.02, 0.8);
  MarkerTracker tracker(TrackOptions{}, ColorModelFromName("red"), s.intrinsics, {0},
                        {s.intrinsics.Project(start)});
  for (int f = 0; f < 14; ++f) {
    const Eigen::Vector3d p = start + Eigen::Vector3d(0.002 * f, 0.0, 0.0);
    RgbdImage image = test::DrawFrame(s, {p});
    const std::array<double, 4> truth = test::DrawnBox(s, p);
    const bool hidden = f >= 8;
    if (hidden) {  // a twig across the lower half of the tape
      const int x0 = static_cast<int>(truth[0]) - 1, x1 = static_cast<int>(truth[0] + truth[2]) + 1;
      const int y0 = static_cast<int>(truth[1] + 0.5 * truth[3]) + 1;
      const int y1 = static_cast<int>(truth[1] + truth[3]) + 1;
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          image.color.at(x, y, 0) = 70;
          image.color.at(x, y, 1) = 60;
          image.color.at(x, y, 2) = 40;
          image.depth.at(x, y) = 700;
        }
      }
    }
    const std::vector<MarkerFrameResult> r = tracker.Step(image, 1.0 / s.fps);
    ASSERT_EQ(r[0].box.state, MarkerState::kTracked) << "frame " << f;
    const std::array<double, 4>& box = r[0].box.box;
    if (!hidden) {
      EXPECT_GT(eval::BoxIou(box, truth), 0.8) << "frame " << f;
    } else {
      // The visible half is half as tall; the box stays the band's.
      EXPECT_NEAR(box[2], truth[2], 0.1 * truth[2]) << "frame " << f;
      EXPECT_NEAR(box[3], truth[3], 0.1 * truth[3]) << "frame " << f;
    }
  }
}

}  // namespace
}  // namespace simtree::tracking::detail
