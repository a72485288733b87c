#include "simtree/report/detail/animation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "simtree/report/detail/base64.h"
#include "simtree/report/detail/quantize.h"

namespace simtree::report {
namespace {

// `branches` vertical branches of `nodes` nodes side by side, swaying at 1.3 Hz with a
// displacement growing towards each tip.
dynamics::NodeFrames SwayingFrames(int branches, int nodes, int frames, double fps = 30) {
  dynamics::NodeFrames f;
  f.fps = fps;
  f.node_count = branches * nodes;
  f.frame_count = frames;
  for (int b = 0; b < branches; ++b) {
    f.branch_first_node.push_back(b * nodes);
    f.branch_node_count.push_back(nodes);
  }
  f.xyz.resize(static_cast<size_t>(frames) * f.node_count * 3);
  for (int k = 0; k < frames; ++k) {
    const double sway = 0.1 * std::sin(2 * M_PI * 1.3 * k / fps);
    for (int b = 0; b < branches; ++b) {
      for (int j = 0; j < nodes; ++j) {
        const double s = j / (nodes - 1.0);
        float* p = &f.xyz[(static_cast<size_t>(k) * f.node_count + b * nodes + j) * 3];
        p[0] = static_cast<float>(0.2 * b + sway * s * s);
        p[1] = static_cast<float>(0.05 * sway * s);
        p[2] = static_cast<float>(3.0 * s);
      }
    }
  }
  return f;
}

TEST(AnimationPlan, SentNodesAreEveryKthNodeAndTheTip) {
  const std::vector<uint32_t> first = {0, 5}, count = {5, 3};
  EXPECT_EQ(SentNodeIndices(first, count, 1), (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(SentNodeIndices(first, count, 2), (std::vector<int>{0, 2, 4, 5, 7}));
  EXPECT_EQ(SentNodeIndices(first, count, 3), (std::vector<int>{0, 3, 4, 5, 7}));
  EXPECT_EQ(SentNodeIndices(first, count, 10), (std::vector<int>{0, 4, 5, 7}));
}

TEST(AnimationPlan, SendsEverythingWhenItFits) {
  const dynamics::NodeFrames f = SwayingFrames(4, 20, 90);
  const AnimationPlan plan = PlanAnimation(f, 10'000'000, 10);
  EXPECT_TRUE(plan.fits);
  EXPECT_EQ(plan.node_stride, 1);
  EXPECT_EQ(plan.frame_stride, 1);
  EXPECT_EQ(plan.sent_nodes, 80);
  EXPECT_EQ(plan.sent_frames, 90);
}

TEST(AnimationPlan, LowersTheFrameRateFirstThenThinsTheNodes) {
  const dynamics::NodeFrames f = SwayingFrames(20, 50, 301);  // 1000 nodes, 10 s at 30 fps
  const int64_t full = PlanAnimation(f, 1'000'000'000, 10).bytes;
  // Half of it: every node at 15 fps.
  AnimationPlan plan = PlanAnimation(f, full / 2 + 20'000, 10);
  EXPECT_TRUE(plan.fits);
  EXPECT_EQ(plan.node_stride, 1);
  EXPECT_EQ(plan.frame_stride, 2);
  EXPECT_LE(plan.bytes, full / 2 + 20'000);
  // A tenth: 10 fps is the floor, so nodes are thinned.
  plan = PlanAnimation(f, full / 10, 10);
  EXPECT_TRUE(plan.fits);
  EXPECT_GT(plan.node_stride, 1);
  EXPECT_GE(f.fps / plan.frame_stride, 10.0 - 1e-9);
  EXPECT_LE(plan.bytes, full / 10);
}

TEST(AnimationPlan, SaysWhenNothingFits) {
  const dynamics::NodeFrames f = SwayingFrames(20, 50, 301);
  EXPECT_FALSE(PlanAnimation(f, 1000, 10).fits);
}

TEST(AnimationPlan, ALongRunOfABigTreeFitsItsBudget) {
  // tree03-like: ~8000 nodes, 12 s at 30 fps (34 MB of floats, a 25 MB glb).
  const dynamics::NodeFrames f = SwayingFrames(400, 20, 361);
  const int64_t budget = 12'000'000;
  const AnimationPlan plan = PlanAnimation(f, budget, 10);
  ASSERT_TRUE(plan.fits);
  EXPECT_LE(plan.bytes, budget);
  EXPECT_GE(f.fps / plan.frame_stride, 10.0 - 1e-9);
  AnimationReport report;
  const nlohmann::json payload = AnimationPayload(f, plan, {}, &report);
  EXPECT_LE(report.bytes, budget);
  EXPECT_GE(report.sent_fps, 10.0);
}

TEST(AnimationPayload, DecodesToTheFramesWithinAQuantisationStep) {
  const dynamics::NodeFrames f = SwayingFrames(3, 9, 61);
  const AnimationPlan plan{2, 3, 0, 0, 0, true};
  AnimationDecor decor;
  decor.radii.assign(f.node_count, 0.0123f);
  decor.branch_level = {0, 1, 1};
  decor.branch_source = {"measured", "interpolated", "default"};
  decor.rope = AnimationDecor::Rope{8, Eigen::Vector3d(1, 2, 0), 0.5, 1.0};
  AnimationReport report;
  const nlohmann::json doc = AnimationPayload(f, plan, decor, &report);
  const std::vector<int> sent = SentNodeIndices(f.branch_first_node, f.branch_node_count, 2);
  ASSERT_EQ(doc["sent_nodes"].get<int>(), static_cast<int>(sent.size()));
  ASSERT_EQ(doc["frames"].get<int>(), 21);  // 0, 3, ..., 60
  EXPECT_NEAR(doc["frame_dt"].get<double>(), 0.1, 1e-12);
  QuantisationBox box;
  for (int a = 0; a < 3; ++a) {
    box.min[a] = doc["box"]["min"][a].get<double>();
    box.step[a] = doc["box"]["step"][a].get<double>();
  }
  const std::vector<float> positions =
      Dequantise(Base64Decode(doc["positions"].get<std::string>()), box);
  ASSERT_EQ(positions.size(), 21 * sent.size() * 3);
  for (int k = 0; k < 21; ++k) {
    for (size_t i = 0; i < sent.size(); ++i) {
      for (int a = 0; a < 3; ++a) {
        const float want = f.xyz[(static_cast<size_t>(3 * k) * f.node_count + sent[i]) * 3 + a];
        EXPECT_NEAR(positions[(k * sent.size() + i) * 3 + a], want, 0.5 * box.step[a] + 2e-6);
      }
    }
  }
  const std::vector<float> rest = Dequantise(Base64Decode(doc["rest"].get<std::string>()), box);
  ASSERT_EQ(rest.size(), static_cast<size_t>(f.node_count) * 3);
  EXPECT_NEAR(rest[3 * 8 + 2], f.xyz[3 * 8 + 2], box.step[2]);
  const std::string radii = Base64Decode(doc["radii"].get<std::string>());
  const int r0 = static_cast<uint8_t>(radii[0]) | static_cast<uint8_t>(radii[1]) << 8;
  EXPECT_NEAR(r0 * doc["radius_step"].get<double>(), 0.0123, 1e-4);
  EXPECT_EQ(doc["branches"][1][3], "interpolated");
  EXPECT_EQ(doc["rope"]["node"], 8);
  EXPECT_EQ(report.sent_frames, 21);
  EXPECT_EQ(report.node_stride, 2);
  EXPECT_NEAR(report.sent_fps, 10.0, 1e-9);
  EXPECT_EQ(report.bytes, static_cast<int64_t>(doc["rest"].get<std::string>().size() +
                                               doc["radii"].get<std::string>().size() +
                                               doc["positions"].get<std::string>().size()));
}

}  // namespace
}  // namespace simtree::report
