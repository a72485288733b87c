#include "simtree/registration/register.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "registration_fixtures.h"
#include "simtree/registration/registration_report.h"

namespace simtree::registration {
namespace {

const MultiViewOptions kDefaults;

const test::StandInViews& Views() {
  static const test::StandInViews views = test::MakeStandInViews(6, 60.0, 21);
  return views;
}

TEST(MultiView, PairsGoAroundTheRing) {
  MultiViewOptions options;
  options.neighbour_span = 2;
  const auto pairs = ViewPairs(6, options);
  EXPECT_EQ(pairs.size(), 12u);  // 6 neighbours + 6 second neighbours
  options.closed_ring = false;
  EXPECT_EQ(ViewPairs(6, options).size(), 9u);  // 5 + 4
  options.neighbour_span = 5;
  options.closed_ring = true;
  EXPECT_EQ(ViewPairs(4, options).size(), 6u);  // every pair once
  EXPECT_TRUE(ViewPairs(1, options).empty());
}

TEST(MultiView, AllViewsRegisterAtTheTree) {
  const auto& v = Views();
  const MultiViewResult result = RegisterViews(v.views, kDefaults);
  ASSERT_EQ(result.RegisteredCount(), 6);
  const int a = result.anchor;
  for (int i = 0; i < 6; ++i) {
    const eval::PoseError e = eval::ViewPoseError(
        result.views[i].frame_from_camera, result.views[a].frame_from_camera,
        v.poses[i].world_from_camera, v.poses[a].world_from_camera, v.tree_points);
    EXPECT_LT(e.rotation_deg, 2.0) << v.views[i].name;
    EXPECT_LT(e.tree_rms_m, 0.02) << v.views[i].name;
    EXPECT_TRUE(result.views[i].verified()) << v.views[i].name;
  }
  // The registration frame stands upright: the anchor's ground is z = 0.
  const RegistrationView& anchor = v.views[a];
  ASSERT_TRUE(anchor.ground);
  const Eigen::Vector3d on_ground = -anchor.ground->offset * anchor.ground->normal;
  EXPECT_NEAR((result.frame_from_anchor.linear() * anchor.ground->normal).z(), 1.0, 1e-9);
  EXPECT_NEAR((result.frame_from_anchor * on_ground).z(), 0.0, 1e-6);
  // The trunk's foot stands on it (its lowest points were cut with the ground's noise band).
  const Eigen::Vector3d foot = result.frame_from_anchor * anchor.trunk->base;
  EXPECT_NEAR(foot.z(), 0.0, 0.05);
  EXPECT_GT(result.merged.points_.size(), 10000u);
}

TEST(MultiView, AViewThatCannotRegisterIsLeftOutNotMerged) {
  std::vector<RegistrationView> views = Views().views;
  views[2].failure = "every pixel is 0";
  views[2].cloud.reset();
  // And a view from another tree entirely: its pairs fail their checks.
  views[4] = test::MakeStandInViews(1, 36.0, 99, {}, "tree02.txt").views[0];
  views[4].name = "view_04";
  const MultiViewResult result = RegisterViews(views, kDefaults);
  EXPECT_FALSE(result.views[2].registered());
  EXPECT_EQ(result.views[2].outcome, ViewOutcome::kCannotRegister);
  EXPECT_EQ(result.views[2].status, "every pixel is 0");
  EXPECT_GE(result.RegisteredCount(), 4);
  for (const PairEdge& edge : result.pairs) {
    if (edge.source == 2 || edge.target == 2) {
      EXPECT_FALSE(edge.used);
    }
  }
  // The report names what was left out, and the picture draws it.
  const std::string table = PairsMarkdown(result);
  EXPECT_NE(table.find("view_02 left out"), std::string::npos) << table;
  const RgbImage picture = BeforeAfterPicture(views, result);
  EXPECT_GT(picture.width, 1000);
  const auto poses = PosesToJson(result);
  EXPECT_EQ(poses["views"][2]["registered"], false);
  EXPECT_TRUE(poses["views"][2]["frame_from_camera"].is_null());
}

TEST(MultiView, NoViewsAndOneView) {
  EXPECT_EQ(RegisterViews({}, kDefaults).RegisteredCount(), 0);
  const MultiViewResult one = RegisterViews({Views().views[0]}, kDefaults);
  EXPECT_EQ(one.RegisteredCount(), 1);
  EXPECT_TRUE(one.pairs.empty());
}

TEST(MultiView, NonsenseOptionsAreRefusedNamingTheField) {
  MultiViewOptions options;
  options.pair.sac_ia.iterations = -3;
  try {
    RegisterViews(Views().views, options);
    FAIL() << "-3 iterations accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "options: pair.sac_ia.iterations: expected >= 1, got -3");
  }
  auto refused = [](auto change) { return test::RefusedFieldAfter<MultiViewOptions>(change); };
  EXPECT_EQ(refused([](MultiViewOptions& o) { o.max_pair_shift_m = 0; }), "max_pair_shift_m");
  EXPECT_EQ(refused([](MultiViewOptions& o) { o.neighbour_span = 0; }), "neighbour_span");
  // An anchor that is no view's index.
  MultiViewOptions beyond;
  beyond.anchor = 6;
  EXPECT_EQ(test::RefusedField(beyond), "");
  EXPECT_THROW(RegisterViews(Views().views, beyond), InputError);
}

}  // namespace
}  // namespace simtree::registration
