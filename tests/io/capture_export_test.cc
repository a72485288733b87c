// A capture folder exported to Azure Kinect recordings and brought back by capture-from: the
// same camera, colour within JPEG loss, depth within rounding, pull times within a millisecond.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/capture_export.h"
#include "simtree/io/capture_from_recordings.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

CameraIntrinsics Camera() {
  CameraIntrinsics k;
  k.width = 1280;
  k.height = 720;
  k.fx = 610;
  k.fy = 612;
  k.cx = 641.2;
  k.cy = 362.7;
  return k;
}

// A smooth picture, and a wall 1.5 m away with a box 1.0 m away in front of it.
RgbdImage Scene(int frame) {
  RgbdImage r;
  r.intrinsics = Camera();
  r.color = RgbImage(1280, 720);
  r.depth = DepthImage(1280, 720, 1500);
  for (int v = 0; v < 720; ++v) {
    for (int u = 0; u < 1280; ++u) {
      const double value = 128 + 90 * std::sin((u + 10 * frame) / 30.0) * std::cos(v / 40.0);
      for (int c = 0; c < 3; ++c) r.color.at(u, v, c) = static_cast<uint8_t>(value);
      if (u > 500 && u < 700 && v > 250 && v < 450) r.depth.at(u, v) = 1000;
    }
  }
  return r;
}

TEST(CaptureExport, ACaptureComesBackThroughRecordings) {
  const fs::path dir = test::TempDir();
  const fs::path original = dir / "original";
  WriteCaptureInfo({"synthetic", "", ""},
                   (fs::create_directories(original), original / "capture.json"));
  WriteScanView(original, "view_00", Scene(0));
  const fs::path pull_dir = original / "pull";
  fs::create_directories(pull_dir);
  WriteIntrinsicsJson(Camera(), pull_dir / "intrinsics.json");
  std::vector<PullFrame> frames;
  for (int i = 0; i < 3; ++i) {
    const RgbdImage s = Scene(i);
    frames.push_back(WritePullFrame(pull_dir, i, i / 30.0, s.color, s.depth));
  }
  WriteFramesCsv(frames, pull_dir / "frames.csv");

  const CaptureExportResult exported = ExportCapture(OpenCapture(original), dir / "rec");
  ASSERT_EQ(exported.scans.size(), 1u);
  EXPECT_EQ(exported.pull_frames, 3);
  CaptureFromOptions options;
  options.scans = exported.scans;
  options.pull = exported.pull;
  options.snap_pull_times = true;  // the export keeps milliseconds: 0, 33, 67 ms
  const CaptureFromResult result = CaptureFromRecordings(options, dir / "back");
  EXPECT_NEAR(result.pull_time_snap_max_s, 0.0005, 1e-9);  // 33 ms -> 33.5 ms

  const Capture back = OpenCapture(dir / "back");
  const RgbdImage view = LoadScanView(back.views[0]);
  EXPECT_NEAR(view.intrinsics.fx, 610, 1e-6);
  EXPECT_NEAR(view.intrinsics.fy, 612, 1e-6);
  EXPECT_NEAR(view.intrinsics.cx, 641.2, 1e-6);
  EXPECT_NEAR(view.intrinsics.cy, 362.7, 1e-6);
  const RgbdImage want = Scene(0);
  double color_error = 0;
  int compared = 0, covered = 0, far_off = 0;
  for (int v = 0; v < 720; ++v) {
    for (int u = 0; u < 1280; ++u) {
      color_error += std::abs(view.color.at(u, v, 1) - want.color.at(u, v, 1));
      // Pixels within 5 of the box's outline may take either surface's depth.
      const bool near_edge_u = std::abs(u - 600) > 95 && std::abs(u - 600) < 105;
      const bool near_edge_v = std::abs(v - 350) > 95 && std::abs(v - 350) < 105;
      if (near_edge_u || near_edge_v) continue;
      ++compared;
      if (view.depth.at(u, v) == 0) continue;
      ++covered;
      far_off += std::abs(view.depth.at(u, v) - want.depth.at(u, v)) > 2;
    }
  }
  EXPECT_LT(color_error / (1280 * 720), 2.0);
  EXPECT_GT(static_cast<double>(covered) / compared, 0.999);
  EXPECT_EQ(far_off, 0);
  ASSERT_EQ(back.pull->frames.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back.pull->frames[i].time_s, i * 0.0335, 1e-6);
}

TEST(CaptureExport, AColourCameraOfNoModesShapeIsRefused) {
  CameraIntrinsics k = Camera();
  k.width = 640;
  k.height = 576;
  const std::string error = test::ErrorOf<InputError>([&] { PinholeAzureCalibrationJson(k); });
  EXPECT_NE(error.find("16:9 or 4:3"), std::string::npos) << error;
}

}  // namespace
}  // namespace simtree
