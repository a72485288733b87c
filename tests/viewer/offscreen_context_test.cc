// The offscreen context's options are checked before any backend is tried (the context itself is
// render_test.cc's).

#include "simtree/viewer/detail/offscreen_context.h"

#include <gtest/gtest.h>

#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(OffscreenOptions, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(OffscreenOptions{}.Validate());
  EXPECT_EQ(test::InputErrorField([] { OffscreenOptions{.width = 0}.Validate(); }), "width");
  EXPECT_EQ(test::InputErrorField([] { OffscreenOptions{.height = 20000}.Validate(); }), "height");
  EXPECT_EQ(test::InputErrorField([] { OffscreenOptions{.samples = -1}.Validate(); }), "samples");
  EXPECT_EQ(test::InputErrorField(
                [] { OffscreenOptions{.backend = static_cast<OffscreenBackend>(7)}.Validate(); }),
            "backend");
}

}  // namespace
}  // namespace simtree::viewer
