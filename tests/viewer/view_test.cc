// The window's options are checked before it opens (the window itself is view_cli_test.cc's).

#include "simtree/viewer/view.h"

#include <gtest/gtest.h>

#include <cmath>

#include "simtree/core/error.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(ViewerOptions, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(ViewerOptions{}.Validate());
  const auto field = [](auto change) {
    ViewerOptions o;
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](ViewerOptions& o) { o.width = 0; }), "width");
  EXPECT_EQ(field([](ViewerOptions& o) { o.height = -5; }), "height");
  EXPECT_EQ(field([](ViewerOptions& o) { o.samples = 64; }), "samples");
  EXPECT_EQ(field([](ViewerOptions& o) { o.fps = NAN; }), "fps");
  EXPECT_EQ(field([](ViewerOptions& o) { o.scene.bark_metres = 0; }), "bark_metres");
  EXPECT_EQ(field([](ViewerOptions& o) { o.dynamics.twist_stiffness_ratio = -1; }),
            "twist_stiffness_ratio");
  EXPECT_EQ(field([](ViewerOptions& o) {
              o.pull = dynamics::PullSchedule{};
              o.pull->release_s = -1;
            }),
            "release_s");
  // The window is not opened for them.
  ViewerOptions bad;
  bad.fps = 0;
  EXPECT_THROW(Viewer(test::ViewerTree(), SceneAssets{}, bad), InputError);
}

}  // namespace
}  // namespace simtree::viewer
