#include "simtree/io/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

using test::ErrorOf;

RgbImage Gradient(int w, int h) {
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.at(x, y, 0) = static_cast<uint8_t>(x * 7);
      image.at(x, y, 1) = static_cast<uint8_t>(y * 11);
      image.at(x, y, 2) = static_cast<uint8_t>((x + y) * 3);
    }
  }
  return image;
}

TEST(ImageIo, ColourRoundTripKeepsEveryPixelAndChannelOrder) {
  const auto dir = test::TempDir();
  const RgbImage image = Gradient(37, 23);
  WritePng(image, dir / "c.png");
  const RgbImage back = ReadColorImage(dir / "c.png");
  EXPECT_EQ(back, image);
  // Red stays red: a channel swap (OpenCV stores BGR) would show here.
  RgbImage red(2, 2);
  for (int i = 0; i < 4; ++i) red.pixels[i * 3] = 255;
  WritePng(red, dir / "red.png");
  EXPECT_EQ(ReadColorImage(dir / "red.png").at(1, 1, 0), 255);
  EXPECT_EQ(ReadColorImage(dir / "red.png").at(1, 1, 2), 0);
}

TEST(ImageIo, DepthRoundTripKeepsSixteenBits) {
  const auto dir = test::TempDir();
  DepthImage depth(640, 576);
  for (size_t i = 0; i < depth.pixels.size(); ++i) depth.pixels[i] = static_cast<uint16_t>(i * 37);
  depth.at(5, 7) = 65535;
  depth.at(6, 7) = 0;
  WritePng(depth, dir / "d.png");
  EXPECT_EQ(ReadDepthImage(dir / "d.png"), depth);
}

TEST(ImageIo, SamePixelsGiveSameBytes) {
  const RgbImage image = Gradient(64, 48);
  EXPECT_EQ(EncodePng(image), EncodePng(image));
  EXPECT_NE(EncodePng(image, {.compression = 0}), EncodePng(image, {.compression = 9}));
}

TEST(ImageIo, BadFilesAreClearErrors) {
  const auto dir = test::TempDir();
  EXPECT_THAT(ErrorOf([&] { ReadColorImage(dir / "none.png"); }), HasSubstr("no such file"));
  test::WriteText(dir / "empty.png", "");
  EXPECT_THAT(ErrorOf([&] { ReadDepthImage(dir / "empty.png"); }),
              HasSubstr("empty.png: expected an image, the file is empty"));
  test::WriteText(dir / "junk.png", "this is not a png");
  EXPECT_THAT(ErrorOf([&] { ReadColorImage(dir / "junk.png"); }),
              HasSubstr("junk.png: expected a PNG, JPEG or BMP image"));
  // A colour image where depth is expected, and 16-bit depth where colour is expected.
  WritePng(Gradient(8, 8), dir / "c.png");
  EXPECT_THAT(ErrorOf([&] { ReadDepthImage(dir / "c.png"); }),
              HasSubstr("expected a 16-bit single-channel depth image (millimetres), got 8-bit "
                        "with 3 channel(s)"));
  WritePng(DepthImage(8, 8, 1000), dir / "d.png");
  EXPECT_THAT(ErrorOf([&] { ReadColorImage(dir / "d.png"); }),
              HasSubstr("expected an 8-bit colour image, got 16-bit"));
  // Truncated file: the header survives, the data does not.
  const std::string bytes = EncodePng(Gradient(64, 64));
  test::WriteText(dir / "cut.png", bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(ErrorOf([&] { ReadColorImage(dir / "cut.png"); }), HasSubstr("cut.png"));
  EXPECT_THAT(ErrorOf([&] { EncodePng(RgbImage()); }), HasSubstr("empty colour image"));
}

// fuzz/png_image's input: a DICOM file ("DICM" at byte 128) that OpenCV handed to GDCM, whose
// reader asserted (abort). Only PNG, JPEG and BMP reach the decoder now.
TEST(ImageIo, OnlyPngJpegAndBmpReachTheDecoder) {
  const std::filesystem::path dicom =
      std::filesystem::path(SIMTREE_SOURCE_DIR) / "fuzz/regressions/png_image/dicom_assert.bin";
  EXPECT_THAT(
      ErrorOf([&] { ReadDepthImage(dicom); }),
      HasSubstr("dicom_assert.bin: expected a PNG, JPEG or BMP image, the file is none of these"));
  EXPECT_THAT(ErrorOf([&] { ReadColorImage(dicom); }), HasSubstr("the file is none of these"));
}

}  // namespace
}  // namespace simtree
