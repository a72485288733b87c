#include "simtree/synth/detail/contact_sheet.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

TEST(ContactSheet, EveryViewAppearsAsColourBesideDepth) {
  std::vector<ContactSheetTile> tiles;
  for (int i = 0; i < 3; ++i) {
    ContactSheetTile t;
    t.label = "view_0" + std::to_string(i);
    t.color = RgbImage(64, 48, static_cast<uint8_t>(40 + 80 * i));
    t.depth = DepthImage(64, 48, 1500);
    tiles.push_back(t);
  }
  ContactSheetOptions options;
  options.columns = 2;
  options.scale = 0.5;
  const RgbImage sheet = MakeContactSheet(tiles, options);
  // Two columns of (32 + gap + 32)-wide cells, two rows.
  EXPECT_GT(sheet.width, 2 * 64);
  EXPECT_GT(sheet.height, 2 * 24);
  // The third view's colour (grey 200) is in the sheet; an empty slot stays background.
  bool found = false;
  for (int y = 0; y < sheet.height && !found; ++y) {
    for (int x = 0; x < sheet.width && !found; ++x) {
      found = sheet.at(x, y, 0) == 200 && sheet.at(x, y, 1) == 200 && sheet.at(x, y, 2) == 200;
    }
  }
  EXPECT_TRUE(found);
}

// Views of another shape (the pull stream's 1280 x 720 colour camera beside 640 x 576 scans) keep
// their shape: the scan is fitted into the wide tile, 72 high and 64 x 72 / 58 = 79 wide, not
// stretched to its 128 columns.
TEST(ContactSheet, ImagesOfAnotherShapeKeepTheirShape) {
  ContactSheetTile scan{"view_00", RgbImage(64, 58, 40), DepthImage(64, 58, 1500)};
  ContactSheetTile pull{"pull", RgbImage(128, 72, 255), DepthImage(128, 72, 1500)};
  ContactSheetOptions options;
  options.columns = 1;
  options.scale = 1.0;
  const RgbImage sheet = MakeContactSheet({scan, pull}, options);
  int rows = 0, widest = 0;
  for (int y = 0; y < sheet.height; ++y) {
    int run = 0;
    for (int x = 0; x < sheet.width; ++x) {
      run += sheet.at(x, y, 0) == 40 && sheet.at(x, y, 1) == 40 && sheet.at(x, y, 2) == 40;
    }
    rows += run >= 10;  // (not a stray label or depth pixel of that grey)
    widest = std::max(widest, run);
  }
  EXPECT_EQ(widest, 79);
  EXPECT_EQ(rows, 72);
}

TEST(ContactSheet, MismatchedOrMissingImagesAreRefused) {
  EXPECT_THROW(MakeContactSheet({}), InputError);
  ContactSheetTile t;
  t.label = "view_00";
  t.color = RgbImage(64, 48);
  t.depth = DepthImage(32, 48);
  EXPECT_THROW(MakeContactSheet({t}), InputError);
}

}  // namespace
}  // namespace simtree::synth
