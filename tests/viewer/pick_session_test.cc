// The picking window's state without a window: markers asked in order, undo and skip, the init
// it gives, the image view's zoom and pan, and its script's mistakes named by line.

#include "simtree/viewer/detail/pick_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/viewer/detail/pick_script.h"
#include "test_util.h"

namespace simtree::viewer::detail {
namespace {

using ::testing::HasSubstr;

std::vector<MarkerLink> ThreeMarkers() {
  return {{.id = 4, .label = "trunk", .parent = -1, .branch = std::nullopt},
          {.id = 7, .label = "", .parent = 4, .branch = std::nullopt},
          {.id = 9, .label = "tip", .parent = 7, .branch = std::nullopt}};
}

TEST(PickSession, AsksEachMarkerInTurnWithUndoAndSkip) {
  PickSession s(ThreeMarkers(), 640, 480);
  EXPECT_EQ(s.Prompt(), "click marker 4 (trunk) (1 of 3)");
  EXPECT_FALSE(s.Click({700, 10}));  // outside the image: still marker 4
  EXPECT_TRUE(s.Click({100.25, 50.5}));
  EXPECT_EQ(s.Prompt(), "click marker 7 (2 of 3)");
  EXPECT_TRUE(s.Click({1, 1}));
  EXPECT_TRUE(s.Undo());  // the click on 7 was wrong
  EXPECT_EQ(s.current()->id, 7);
  EXPECT_TRUE(s.Skip());
  EXPECT_TRUE(s.Click({300, 200}));
  EXPECT_TRUE(s.complete());
  EXPECT_FALSE(s.Click({5, 5}));
  EXPECT_FALSE(s.Skip());
  EXPECT_THAT(s.Prompt(), HasSubstr("2 of 3 markers clicked, 1 skipped"));
  const TrackInit init = s.ToInit(12);
  EXPECT_EQ(init.frame, 12);
  ASSERT_EQ(init.markers.size(), 2u);
  EXPECT_EQ(init.markers[0].id, 4);
  EXPECT_EQ(init.markers[0].pixel, Eigen::Vector2d(100.25, 50.5));
  EXPECT_EQ(init.markers[1].id, 9);
}

TEST(PickSession, NothingClickedGivesNoInit) {
  PickSession s(ThreeMarkers(), 640, 480);
  EXPECT_FALSE(s.Undo());
  s.Skip(), s.Skip(), s.Skip();
  EXPECT_THAT(test::ErrorOf([&] { s.ToInit(0); }), HasSubstr("no marker was clicked"));
}

TEST(ImageView, FitsCentresAndZoomsAboutThePointer) {
  ImageView v = ImageView::Fit(640, 480, 1280, 800);
  EXPECT_DOUBLE_EQ(v.zoom, 800.0 / 480.0);
  // The image's corners land symmetrically in the window.
  const Eigen::Vector2d lo = v.ToWindow({-0.5, -0.5}), hi = v.ToWindow({639.5, 479.5});
  EXPECT_NEAR(lo.x(), 1280 - hi.x(), 1e-9);
  EXPECT_NEAR(lo.y(), 0.0, 1e-9);
  EXPECT_NEAR(hi.y(), 800.0, 1e-9);
  const Eigen::Vector2d pointer(700, 300);
  const Eigen::Vector2d under = v.ToImage(pointer);
  v.ZoomAbout(pointer, 4.0);
  EXPECT_TRUE(v.ToImage(pointer).isApprox(under, 1e-12));
  v.Pan({10, -20});
  EXPECT_TRUE(v.ToImage(pointer + Eigen::Vector2d(10, -20)).isApprox(under, 1e-12));
  v.ZoomAbout(pointer, 1e6);
  EXPECT_DOUBLE_EQ(v.zoom, 64.0);
}

TEST(PickScript, ParsesActionsAndNamesTheLineOfAMistake) {
  const auto actions = ParsePickScript(
      "# pick two\nzoom 3\nzoom 2 100 50\npan -5 7\nclick 10 20\nclick-image 3.5 4\n"
      "key backspace\nkey s\nwait 3\nkey enter\n",
      "s.txt");
  ASSERT_EQ(actions.size(), 9u);
  EXPECT_EQ(actions[0].verb, PickVerb::kZoom);
  EXPECT_EQ(actions[1].numbers, (std::vector<double>{2, 100, 50}));
  EXPECT_EQ(actions[4].verb, PickVerb::kClickImage);
  EXPECT_EQ(actions[6].key, "s");
  EXPECT_EQ(actions[8].line, 10);
  EXPECT_THAT(test::ErrorOf([] { ParsePickScript("click 1\n", "s.txt"); }),
              HasSubstr("s.txt: line 1: click takes 2 numbers, got 1"));
  EXPECT_THAT(test::ErrorOf([] { ParsePickScript("\nkey q\n", "s.txt"); }),
              HasSubstr("line 2: expected a key backspace, s, enter or escape"));
  EXPECT_THAT(test::ErrorOf([] { ParsePickScript("tap 1 2\n", "s.txt"); }),
              HasSubstr("unknown action \"tap\""));
  EXPECT_THAT(test::ErrorOf([] { ParsePickScript("pan 1 x\n", "s.txt"); }),
              HasSubstr("expected a number, got \"x\""));
}

}  // namespace
}  // namespace simtree::viewer::detail
