#include "simtree/io/capture.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::ErrorOf;

CameraIntrinsics SmallIntrinsics() {
  CameraIntrinsics k;
  k.width = 32;
  k.height = 24;
  k.fx = k.fy = 25.0;
  k.cx = 15.5;
  k.cy = 11.5;
  return k;
}

RgbdImage SmallImage(uint16_t depth_mm) {
  RgbdImage image;
  image.intrinsics = SmallIntrinsics();
  image.color = RgbImage(32, 24, 90);
  image.depth = DepthImage(32, 24, depth_mm);
  return image;
}

// A capture with two views and a three-frame pull stream.
fs::path MakeCapture(const fs::path& root) {
  WriteCaptureInfo({"synthetic test", "acer_rubrum", "made by a test"}, root / "capture.json");
  WriteScanView(root, "view_01", SmallImage(2000));
  WriteScanView(root, "view_00", SmallImage(1500));
  std::vector<PullFrame> frames;
  for (int i = 0; i < 3; ++i) {
    frames.push_back(WritePullFrame(root / "pull", i, i / 30.0, RgbImage(32, 24, 10),
                                    DepthImage(32, 24, static_cast<uint16_t>(1000 + i))));
  }
  WriteFramesCsv(frames, root / "pull" / "frames.csv");
  WriteIntrinsicsJson(SmallIntrinsics(), root / "pull" / "intrinsics.json");
  WriteMarkersJson({{0, "M0", -1, 0}, {1, "M1", 0, 3}, {2, "M2", 1, std::nullopt}},
                   root / "pull" / "markers.json");
  return root;
}

TEST(Capture, IntrinsicsProjectAndUnprojectAreInverse) {
  CameraIntrinsics k{640, 576, 504.3, 504.1, 321.0, 333.5, 0.001};
  const Eigen::Vector3d p(0.31, -0.42, 2.2);
  const Eigen::Vector2d uv = k.Project(p);
  EXPECT_TRUE(k.Unproject(uv.x(), uv.y(), p.z()).isApprox(p, 1e-12));
  // The principal point looks straight down the optical axis.
  EXPECT_TRUE(k.Unproject(k.cx, k.cy, 3.0).isApprox(Eigen::Vector3d(0, 0, 3), 1e-12));
  EXPECT_NEAR(k.HorizontalFov(), std::atan(321.5 / 504.3) + std::atan(318.5 / 504.3), 1e-12);
}

TEST(Capture, WritesAndReadsBackEverything) {
  const fs::path root = MakeCapture(test::TempDir() / "capture");
  const Capture capture = OpenCapture(root);
  EXPECT_EQ(capture.info.sensor, "synthetic test");
  EXPECT_EQ(capture.info.species, "acer_rubrum");
  ASSERT_EQ(capture.views.size(), 2u);
  EXPECT_EQ(capture.views[0].name, "view_00");  // sorted, whatever the directory order
  EXPECT_EQ(capture.views[0].intrinsics, SmallIntrinsics());
  const RgbdImage view1 = LoadScanView(capture.views[1]);
  EXPECT_EQ(view1.depth.at(3, 4), 2000);
  EXPECT_EQ(view1.color.at(3, 4, 1), 90);

  ASSERT_TRUE(capture.pull.has_value());
  const PullStream& pull = *capture.pull;
  ASSERT_EQ(pull.frames.size(), 3u);
  EXPECT_EQ(pull.frames[2].color, "color/000002.png");
  EXPECT_NEAR(pull.frames[2].time_s, 2.0 / 30.0, 1e-6);
  EXPECT_NEAR(pull.FrameRate(), 30.0, 1e-3);
  EXPECT_EQ(LoadPullFrame(pull, 2).depth.at(0, 0), 1002);
  ASSERT_TRUE(pull.has_markers);
  ASSERT_EQ(pull.markers.size(), 3u);
  EXPECT_EQ(pull.markers[1], (MarkerLink{1, "M1", 0, 3}));
  EXPECT_FALSE(pull.markers[2].branch.has_value());
}

TEST(Capture, MissingPiecesAreNamed) {
  const fs::path root = MakeCapture(test::TempDir() / "capture");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root / "nothere"); }),
              HasSubstr("expected a capture folder, no such folder"));
  fs::remove(root / "scans" / "view_01" / "color.png");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root); }),
              HasSubstr("view_01/color.png: missing (colour image of view view_01)"));
  WriteScanView(root, "view_01", SmallImage(1));
  fs::remove(root / "pull" / "depth" / "000001.png");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root); }),
              HasSubstr("000001.png: missing (depth image of frame 1 named in frames.csv)"));
  fs::remove_all(root / "pull");
  fs::remove(root / "scans" / "view_00" / "intrinsics.json");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root); }),
              HasSubstr("view_00/intrinsics.json: missing (camera intrinsics JSON)"));
  fs::remove_all(root / "scans");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root); }),
              HasSubstr("expected scans/ (multi-view scans) or pull/"));
  fs::remove(root / "capture.json");
  EXPECT_THAT(ErrorOf([&] { OpenCapture(root); }), HasSubstr("capture.json: missing"));
}

TEST(Capture, ImagesMustMatchTheirIntrinsics) {
  const fs::path root = MakeCapture(test::TempDir() / "capture");
  const fs::path view = root / "scans" / "view_00";
  // A colour image of another size (e.g. the Kinect's 1280x720 colour not registered to depth).
  WritePng(RgbImage(64, 48), view / "color.png");
  EXPECT_THAT(ErrorOf([&] { LoadScanView(OpenCapture(root).views[0]); }),
              HasSubstr("color.png: expected 32x24 pixels (the size in intrinsics.json), got "
                        "64x48"));
  WritePng(RgbImage(32, 24), view / "color.png");
  // Intrinsics written for another mode than the images.
  CameraIntrinsics wfov = SmallIntrinsics();
  wfov.width = 1024;
  wfov.height = 1024;
  WriteIntrinsicsJson(wfov, view / "intrinsics.json");
  EXPECT_THAT(ErrorOf([&] { LoadScanView(OpenCapture(root).views[0]); }),
              HasSubstr("expected 1024x1024 pixels (the size in intrinsics.json), got 32x24"));
  WriteIntrinsicsJson(SmallIntrinsics(), view / "intrinsics.json");
  WritePng(DepthImage(32, 24, 0), view / "depth.png");
  EXPECT_THAT(ErrorOf([&] { LoadScanView(OpenCapture(root).views[0]); }),
              HasSubstr("depth.png: expected depth measurements, every pixel is 0"));
  // An 8-bit depth image cannot hold millimetres.
  WritePng(RgbImage(32, 24, 7), view / "depth.png");
  EXPECT_THAT(ErrorOf([&] { LoadScanView(OpenCapture(root).views[0]); }),
              HasSubstr("expected a 16-bit single-channel depth image"));
  // Writers refuse the same mistakes.
  RgbdImage bad = SmallImage(0);
  EXPECT_THAT(ErrorOf([&] { WriteScanView(root, "view_09", bad); }), HasSubstr("every pixel is 0"));
  EXPECT_FALSE(fs::exists(root / "scans" / "view_09" / "depth.png"));
}

TEST(Capture, BadIntrinsicsAreClearErrors) {
  const fs::path dir = test::TempDir();
  const auto read = [&](const std::string& text) {
    test::WriteText(dir / "intrinsics.json", text);
    return ErrorOf([&] { ReadIntrinsicsJson(dir / "intrinsics.json"); });
  };
  EXPECT_THAT(read(R"({"width": 640, "height": 576, "fx": -504, "fy": 504, "cx": 320,
                       "cy": 288, "depth_scale_m": 0.001})"),
              HasSubstr("fx: expected a positive focal length in pixels, got -504"));
  EXPECT_THAT(read(R"({"width": 640, "height": 576, "fx": 504, "fy": 504, "cx": 320,
                       "cy": 288})"),
              HasSubstr("depth_scale_m: missing"));
  EXPECT_THAT(read(R"({"width": 640, "height": 576, "fx": 504, "fy": 504, "cx": 320,
                       "cy": 288, "depth_scale_m": 1000})"),
              HasSubstr("expected metres per depth unit"));
  EXPECT_THAT(read(R"({"width": 0, "height": 576, "fx": 504, "fy": 504, "cx": 320,
                       "cy": 288, "depth_scale_m": 0.001})"),
              HasSubstr("expected an image size between 1 and"));
  EXPECT_THAT(read(R"({"width": 640, "height": 576, "fx": 504, "fy": 504, "cx": 5000,
                       "cy": 288, "depth_scale_m": 0.001})"),
              HasSubstr("cx: expected a principal point near the image"));
  EXPECT_THAT(read(R"({"width": "640"})"), HasSubstr("width: expected an integer"));
  EXPECT_THAT(read("{"), HasSubstr("intrinsics.json: line 1"));
}

TEST(Capture, BadFramesCsvIsAClearError) {
  const fs::path root = MakeCapture(test::TempDir() / "capture");
  const fs::path csv = root / "pull" / "frames.csv";
  const auto open = [&](const std::string& text) {
    test::WriteText(csv, text);
    return ErrorOf([&] { OpenCapture(root); });
  };
  EXPECT_THAT(open(""), HasSubstr("expected the header"));
  EXPECT_THAT(open("frame,time,color,depth\n"), HasSubstr("line 1: expected the header"));
  EXPECT_THAT(open("frame,time_s,color,depth\n"), HasSubstr("expected at least one frame"));
  EXPECT_THAT(open("frame,time_s,color,depth\n0,0,color/000000.png\n"),
              HasSubstr("line 2: expected 4 cells"));
  EXPECT_THAT(open("frame,time_s,color,depth\nzero,0,color/000000.png,depth/000000.png\n"),
              HasSubstr("line 2, frame: expected an integer frame number"));
  EXPECT_THAT(open("frame,time_s,color,depth\n0,nan,color/000000.png,depth/000000.png\n"),
              HasSubstr("line 2, time_s: expected a finite time"));
  EXPECT_THAT(open("frame,time_s,color,depth\n1,0.1,color/000001.png,depth/000001.png\n"
                   "0,0.2,color/000000.png,depth/000000.png\n"),
              HasSubstr("line 3, frame: expected frames in increasing order, got 0 after 1"));
  EXPECT_THAT(open("frame,time_s,color,depth\n0,0.1,color/000000.png,depth/000000.png\n"
                   "1,0.1,color/000001.png,depth/000001.png\n"),
              HasSubstr("line 3, time_s: expected increasing times"));
  EXPECT_THAT(open("frame,time_s,color,depth\n0,0,/tmp/x.png,depth/000000.png\n"),
              HasSubstr("expected a path relative to pull/"));
  EXPECT_THAT(open("frame,time_s,color,depth\n0,0,../x.png,depth/000000.png\n"),
              HasSubstr("expected a path inside pull/"));
  // Windows line endings and comments are fine.
  test::WriteText(csv,
                  "# written by hand\r\nframe,time_s,color,depth\r\n"
                  "0,0.0,color/000000.png,depth/000000.png\r\n");
  EXPECT_EQ(OpenCapture(root).pull->frames.size(), 1u);
}

TEST(Capture, BadMarkersJsonIsAClearError) {
  const fs::path dir = test::TempDir();
  const auto read = [&](const std::string& markers) {
    test::WriteText(dir / "markers.json",
                    R"({"format": "simtree.markers", "version": 1, "markers": )" + markers + "}");
    return ErrorOf([&] { ReadMarkersJson(dir / "markers.json"); });
  };
  EXPECT_THAT(read("[]"), HasSubstr("expected at least one marker"));
  EXPECT_THAT(read(R"([{"id": 0, "parent": -1}, {"id": 0, "parent": 0}])"),
              HasSubstr("markers[1].id: marker id 0 appears twice"));
  EXPECT_THAT(read(R"([{"id": 0, "parent": -1}, {"id": 1, "parent": 7}])"),
              HasSubstr("markers[1].parent: marker 1 links to marker 7, which is not in the list"));
  EXPECT_THAT(read(R"([{"id": 0, "parent": -1}, {"id": 1, "parent": 2}, {"id": 2, "parent": 1}])"),
              HasSubstr("form a cycle"));
  EXPECT_THAT(read(R"([{"id": 0, "parent": -1}, {"id": 1, "parent": -1}])"),
              HasSubstr("expected exactly one root marker"));
  EXPECT_THAT(read(R"([{"id": 0, "parent": -1, "branch": -2}])"),
              HasSubstr("expected a branch id >= 0"));
  EXPECT_THAT(read(R"([{"id": 0}])"), HasSubstr("markers[0].parent: missing"));
  EXPECT_EQ(read(R"([{"id": 4, "parent": -1}])"), "");
  EXPECT_EQ(ReadMarkersJson(dir / "markers.json")[0].label, "M4");  // a default label
  test::WriteText(dir / "markers.json", R"({"format": "simtree.tree", "version": 1})");
  EXPECT_THAT(ErrorOf([&] { ReadMarkersJson(dir / "markers.json"); }),
              HasSubstr("format: expected \"simtree.markers\", got \"simtree.tree\""));
}

}  // namespace
}  // namespace simtree
