#include "simtree/registration/detail/cloud_picture.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"

namespace simtree::registration {
namespace {

TEST(CloudPicture, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(PictureOptions{}), "");
  auto refused = [](auto change) { return test::RefusedFieldAfter<PictureOptions>(change); };
  EXPECT_EQ(refused([](PictureOptions& o) { o.panel_width = 10; }), "panel_width");
  EXPECT_EQ(refused([](PictureOptions& o) { o.side_direction = Eigen::Vector3d::UnitZ(); }),
            "side_direction");
}

TEST(CloudPicture, PanelsSideBySide) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 0, 2}};
  const PicturePanel panel{"one", {{&points, ViewColor(0), 2}}};
  const RgbImage picture = DrawPanels({panel, panel});
  EXPECT_EQ(picture.width, 2 * PictureOptions{}.panel_width);
  EXPECT_THROW(DrawPanels({}), InputError);
}

}  // namespace
}  // namespace simtree::registration
