// The scene's options are checked before any drawing (the drawing itself is render_test.cc's).

#include "simtree/viewer/scene_renderer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(SceneOptions, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(SceneOptions{}.Validate());
  const auto field = [](auto change) {
    SceneOptions o;
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](SceneOptions& o) { o.tube.sides = 2; }), "tube.sides");
  EXPECT_EQ(field([](SceneOptions& o) { o.tube.min_radius = NAN; }), "tube.min_radius");
  EXPECT_EQ(field([](SceneOptions& o) { o.bark_metres = 0; }), "bark_metres");
  EXPECT_EQ(field([](SceneOptions& o) { o.grid_spacing_m = -1; }), "grid_spacing_m");
  EXPECT_EQ(field([](SceneOptions& o) { o.petiole_sides = 1; }), "petiole_sides");
  EXPECT_EQ(field([](SceneOptions& o) { o.leaf_detail.tolerance = -1; }), "tolerance");
}

}  // namespace
}  // namespace simtree::viewer
