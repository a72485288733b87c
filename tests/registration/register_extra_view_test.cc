#include "simtree/registration/register_extra_view.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "registration_fixtures.h"
#include "simtree/registration/registration_report.h"
#include "test_util.h"

namespace simtree::registration {
namespace {

// Views 45 deg apart around the stand-in tree; views 0, 1, 3 and 4 registered (an open ring),
// view 2 the extra view between 1 and 3.
struct Registered {
  test::StandInViews scene;
  std::vector<RegistrationView> views;
  MultiViewResult result;
};

const Registered& Scene() {
  static const Registered registered = [] {
    Registered r;
    r.scene = test::MakeStandInViews(5, 45.0, 31);
    r.views = {r.scene.views[0], r.scene.views[1], r.scene.views[3], r.scene.views[4]};
    MultiViewOptions options;
    options.closed_ring = false;
    r.result = RegisterViews(r.views, options);
    return r;
  }();
  return registered;
}

TEST(ExtraView, IsPlacedWhereItsCameraStood) {
  const Registered& r = Scene();
  ASSERT_EQ(r.result.RegisteredCount(), 4);
  const ExtraViewOptions options;
  const ExtraViewResult extra = RegisterExtraView(r.views, r.result, r.scene.views[2], options);
  ASSERT_TRUE(extra.placed()) << extra.status;
  EXPECT_EQ(extra.outcome, ExtraViewOutcome::kPlaced) << extra.status;
  EXPECT_GE(extra.pairs_used, 2);
  EXPECT_EQ(extra.pairs.size(), 4u);
  EXPECT_LE(extra.rotation_spread_deg, options.max_rotation_deg);
  // Against the truth, relative to the first view.
  const eval::PoseError e = eval::ViewPoseError(
      extra.frame_from_camera, r.result.views[0].frame_from_camera,
      r.scene.poses[2].world_from_camera, r.scene.poses[0].world_from_camera, r.scene.tree_points);
  EXPECT_LT(e.rotation_deg, 1.0);
  EXPECT_LT(e.tree_rms_m, 0.015);
  // pull_camera.json gives the pose back.
  const auto path = test::TempDir() / "pull_camera.json";
  test::WriteText(path, ExtraViewToJson(extra).dump(1));
  const auto back = ReadPullCameraJson(path);
  ASSERT_TRUE(back);
  EXPECT_LT((back->matrix() - extra.frame_from_camera.matrix()).norm(), 1e-9);
}

TEST(ExtraView, AViewNoPairPlacesIsReportedNotPlaced) {
  const Registered& r = Scene();
  RegistrationView no_trunk = r.scene.views[2];
  no_trunk.failure = "no trunk: the bottom of the view holds no upright stem";
  const ExtraViewOptions options;
  const ExtraViewResult cannot = RegisterExtraView(r.views, r.result, no_trunk, options);
  EXPECT_EQ(cannot.outcome, ExtraViewOutcome::kCannotRegister);
  EXPECT_FALSE(cannot.placed());
  EXPECT_EQ(cannot.status, no_trunk.failure);
  // Checks no pair can pass (and no retries): every pair fails, with its reason.
  ExtraViewOptions strict;
  strict.pair.min_fitness = 0.99;
  strict.pair.retry_other_key_regions = strict.pair.retry_with_shifts = false;
  strict.pair.retry_without_priors = false;
  const ExtraViewResult refused = RegisterExtraView(r.views, r.result, r.scene.views[2], strict);
  EXPECT_EQ(refused.outcome, ExtraViewOutcome::kNoTrustedPair);
  EXPECT_NE(refused.status.find("at least 99%"), std::string::npos) << refused.status;
  const auto path = test::TempDir() / "pull_camera.json";
  test::WriteText(path, ExtraViewToJson(refused).dump(1));
  EXPECT_FALSE(ReadPullCameraJson(path));
}

TEST(ExtraView, NonsenseOptionsAreRefused) {
  auto refused = [](auto change) { return test::RefusedFieldAfter<ExtraViewOptions>(change); };
  const ExtraViewOptions options;
  EXPECT_EQ(test::RefusedField(options), "");
  EXPECT_EQ(refused([](ExtraViewOptions& o) { o.max_pairs = 0; }), "max_pairs");
  EXPECT_EQ(refused([](ExtraViewOptions& o) { o.pair.min_fitness = -1; }), "pair.min_fitness");
  // Views that are not what was registered.
  EXPECT_THROW(RegisterExtraView({}, Scene().result, Scene().scene.views[2], options), InputError);
}

}  // namespace
}  // namespace simtree::registration
