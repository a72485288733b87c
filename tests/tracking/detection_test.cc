#include "simtree/tracking/detail/detection.h"
#include "simtree/eval/tracking_metrics.h"

#include <gtest/gtest.h>

#include "drawn_stream.h"

namespace simtree::tracking::detail {
namespace {

std::vector<Detection> DetectAll(const RgbdImage& image) {
  BlobDetector detector(ColorModelFromName("red"), BlobDetectorOptions{});
  const SearchWindow all{0, 0, image.color.width, image.color.height};
  std::vector<Detection> out;
  for (const Blob& b : detector.Find(image, {all})) {
    out.push_back(MeasureBlob(b, image, detector, MeasureOptions{}));
  }
  return out;
}

TEST(Detection, SubPixelCentreBoxAndAxisDepthOfADrawnBand) {
  test::DrawnStream s;
  const Eigen::Vector3d p(0.0123, -0.0371, 1.6);  // projects between pixel centres
  const RgbdImage image = test::DrawFrame(s, {p});
  const std::vector<Detection> found = DetectAll(image);
  ASSERT_EQ(found.size(), 1u);
  const Detection& d = found[0];
  const Eigen::Vector2d truth = s.intrinsics.Project(p);
  EXPECT_LT((d.center - truth).norm(), 0.15) << d.center.transpose() << " vs " << truth.transpose();
  EXPECT_GT(eval::BoxIou(d.Box(), test::DrawnBox(s, p)), 0.75);
  ASSERT_TRUE(d.has_depth);
  EXPECT_LT((d.position - p).norm(), 0.004);
}

TEST(Detection, CrossingBandsAtDifferentDepthsSplitIntoTwo) {
  test::DrawnStream s;
  const Eigen::Vector3d near(0.0, 0.0, 1.5), far(0.01, 0.03, 1.9);  // overlapping in the image
  const RgbdImage image = test::DrawFrame(s, {near, far});
  const std::vector<Detection> found = DetectAll(image);
  ASSERT_EQ(found.size(), 2u);
  std::vector<double> z = {found[0].position.z(), found[1].position.z()};
  std::sort(z.begin(), z.end());
  EXPECT_NEAR(z[0], near.z(), 0.01);
  EXPECT_NEAR(z[1], far.z(), 0.01);
}

TEST(Detection, ABranchReadingWhereTheTapeHasFewDepthPixels) {
  // A thin tape whose own depth pixels are holes but two that read what lies behind it (the
  // sensor mixes them), on a branch whose pixels around the tape read right.
  test::DrawnStream s;
  const Eigen::Vector3d p(0.0123, -0.0371, 1.6);
  RgbdImage image = test::DrawFrame(s, {p});
  const auto box = test::DrawnBox(s, p);
  const uint16_t surface = static_cast<uint16_t>(std::lround(1000.0 * (p.z() - 0.85 * s.radius_m)));
  int fliers = 0;
  for (int y = int(box[1]) - 3; y <= int(box[1] + box[3]) + 3; ++y) {
    for (int x = int(box[0]) - 1; x <= int(box[0] + box[2]) + 1; ++x) {
      const bool tape = image.depth.at(x, y) == surface;
      image.depth.at(x, y) = !tape ? surface : (fliers++ < 2 ? 1900 : 0);
    }
  }
  const std::vector<Detection> found = DetectAll(image);
  ASSERT_EQ(found.size(), 1u);
  const Detection& d = found[0];
  ASSERT_TRUE(d.has_depth);
  EXPECT_GT(std::abs(d.position.z() - p.z()), 0.2);  // the tape's own reading is the flier's
  ASSERT_TRUE(d.has_branch_depth);
  Eigen::Vector3d again;
  ASSERT_TRUE(RemeasureNear(d, image.intrinsics, p.z(), 0.03, &again));
  EXPECT_LT((again - p).norm(), 0.006);
  // A prediction the branch does not fit gets nothing.
  EXPECT_FALSE(RemeasureNear(d, image.intrinsics, p.z() + 0.2, 0.03, &again));
}

TEST(Detection, RobustDepthIgnoresFlyingPixelsAndHoles) {
  DepthImage depth(5, 1);
  depth.pixels = {1500, 1502, 0, 1501, 3000};  // a hole and a background pixel
  const double z = RobustDepth(depth, 0.001, {0, 1, 2, 3, 4}, 0.03);
  EXPECT_NEAR(z, 1.501, 0.0015);
  EXPECT_EQ(RobustDepth(depth, 0.001, {2}, 0.03), 0.0);
}

}  // namespace
}  // namespace simtree::tracking::detail
