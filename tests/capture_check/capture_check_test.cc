#include "simtree/capture_check/capture_check.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "quick_capture.h"
#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/image_io.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::capture_check {
namespace {

TEST(CaptureCheck, ASynthCaptureHasNoFailure) {
  const CaptureCheckResult r = CheckCapture(QuickCapture(), NoRegistration());
  EXPECT_EQ(r.Count(Status::kFail), 0) << FormatTable(r);
  for (const std::string view : {"view_00", "view_01", "view_02", "view_03"}) {
    EXPECT_EQ(Find(r, "depth on the tree", view).status, Status::kOk) << FormatTable(r);
    EXPECT_EQ(Find(r, "exposure", view).status, Status::kOk);
    EXPECT_EQ(Find(r, "blur", view).status, Status::kOk);
  }
  const Check tape = Find(r, "tape markers", "pull frame 0");
  EXPECT_GE(tape.value, 8) << tape.message;
  EXPECT_EQ(Find(r, "dropped frames", "pull").status, Status::kOk);
  EXPECT_EQ(Find(r, "view coverage", "scans").status, Status::kSkipped);
  const nlohmann::ordered_json j = ToJson(r);
  EXPECT_EQ(j["format"], "simtree.capture_check");
  EXPECT_EQ(j["checks"].size(), r.checks.size());
}

TEST(CaptureCheck, ZeroedDepthFails) {
  const fs::path dir = CopyOfCapture();
  const fs::path v1 = dir / "scans" / "view_01" / "depth.png";
  WritePng(DepthImage(640, 576, 0), v1);
  // view_02: two pixels of three without depth.
  const fs::path v2 = dir / "scans" / "view_02" / "depth.png";
  DepthImage d = ReadDepthImage(v2);
  for (size_t i = 0; i < d.pixels.size(); ++i) {
    if (i % 3 != 0) d.pixels[i] = 0;
  }
  WritePng(d, v2);
  const CaptureCheckResult r = CheckCapture(dir, NoRegistration());
  EXPECT_EQ(r.Worst(), Status::kFail);
  const Check whole = Find(r, "images", "view_01");
  EXPECT_EQ(whole.status, Status::kFail);
  EXPECT_NE(whole.message.find("depth"), std::string::npos) << whole.message;
  const Check part = Find(r, "depth on the tree", "view_02");
  EXPECT_EQ(part.status, Status::kFail) << part.message;
  EXPECT_NE(part.message.find("depth drops out"), std::string::npos) << part.message;
}

TEST(CaptureCheck, DroppedFramesFail) {
  const fs::path dir = CopyOfCapture();
  std::vector<PullFrame> frames = ReadFramesCsv(dir / "pull" / "frames.csv");
  std::vector<PullFrame> kept;
  for (const PullFrame& f : frames) {
    if (f.frame == 0 || f.frame % 8 != 0) kept.push_back(f);
  }
  WriteFramesCsv(kept, dir / "pull" / "frames.csv");
  const CaptureCheckResult r = CheckCapture(dir, NoRegistration());
  const Check c = Find(r, "dropped frames", "pull");
  EXPECT_EQ(c.status, Status::kFail);
  EXPECT_NE(c.message.find(std::to_string(frames.size() - kept.size()) + " frames dropped"),
            std::string::npos)
      << c.message;
  EXPECT_NE(c.message.find("recorder could not keep up"), std::string::npos) << c.message;
}

TEST(CaptureCheck, OverexposedColourFails) {
  const fs::path dir = CopyOfCapture();
  const fs::path color = dir / "pull" / "color" / "000000.png";
  RgbImage c = ReadColorImage(color);
  for (uint8_t& v : c.pixels) v = static_cast<uint8_t>(std::min(255, v * 8));
  WritePng(c, color);
  const CaptureCheckResult r = CheckCapture(dir, NoRegistration());
  const Check e = Find(r, "exposure", "pull frame 0");
  EXPECT_EQ(e.status, Status::kFail) << e.message;
  EXPECT_NE(e.message.find("clipped white"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("lower the exposure"), std::string::npos) << e.message;
  EXPECT_EQ(Find(r, "exposure", "view_00").status, Status::kOk);
}

// Each channel averaged over a box of (2 radius + 1) px along rows, then along columns.
RgbImage BoxBlurred(const RgbImage& image, int radius) {
  RgbImage out = image;
  for (const bool rows : {true, false}) {
    const RgbImage in = out;
    for (int y = 0; y < in.height; ++y) {
      for (int x = 0; x < in.width; ++x) {
        for (int ch = 0; ch < 3; ++ch) {
          int sum = 0, n = 0;
          for (int d = -radius; d <= radius; ++d) {
            const int xx = rows ? x + d : x, yy = rows ? y : y + d;
            if (xx < 0 || yy < 0 || xx >= in.width || yy >= in.height) continue;
            sum += in.at(xx, yy, ch);
            ++n;
          }
          out.at(x, y, ch) = static_cast<uint8_t>((sum + n / 2) / n);
        }
      }
    }
  }
  return out;
}

TEST(CaptureCheck, ABlurredPullFrameWarns) {
  const fs::path dir = CopyOfCapture();
  const fs::path color = dir / "pull" / "color" / "000000.png";
  WritePng(BoxBlurred(ReadColorImage(color), 2), color);
  const CaptureCheckResult r = CheckCapture(dir, NoRegistration());
  const Check blur = Find(r, "blur", "pull frame 0");
  EXPECT_EQ(blur.status, Status::kWarn) << blur.message;
  EXPECT_NE(blur.message.find("hold the camera still"), std::string::npos) << blur.message;
  EXPECT_EQ(Find(r, "blur", "view_00").status, Status::kOk);
}

TEST(CaptureCheck, AMissingViewWarns) {
  const fs::path dir = CopyOfCapture();
  fs::remove_all(dir / "scans" / "view_02");
  const CaptureCheckResult r = CheckCapture(dir, NoRegistration());
  const Check views = Find(r, "scan views", "scans");
  EXPECT_EQ(views.status, Status::kWarn);
  EXPECT_NE(views.message.find("3 views: take at least 4 views"), std::string::npos)
      << views.message;
  EXPECT_NE(FormatTable(r).find("warn scans (scan views): 3 views"), std::string::npos)
      << FormatTable(r);
}

// The pull stream as an Open3D folder (color/, depth/ in millimetres, intrinsic.json): checked
// through capture-from, with the conversion's own count of drops.
TEST(CaptureCheck, RecordingsAreCheckedThroughCaptureFrom) {
  const fs::path rec = test::TempDir() / "pull_open3d";
  fs::create_directories(rec / "color");
  fs::create_directories(rec / "depth");
  const fs::path pull = QuickCapture() / "pull";
  for (int i = 0; i < 12; ++i) {
    const std::string name = fmt::format("{:06d}.png", i);
    fs::copy_file(pull / "color" / name, rec / "color" / name);
    fs::copy_file(pull / "depth" / name, rec / "depth" / name);
  }
  const CameraIntrinsics k = ReadIntrinsicsJson(pull / "intrinsics.json");
  test::WriteText(rec / "intrinsic.json",
                  fmt::format(R"({{"width": {}, "height": {}, "intrinsic_matrix": [{}, 0, 0, 0, )"
                              R"({}, 0, {}, {}, 1]}})",
                              k.width, k.height, k.fx, k.fy, k.cx, k.cy));
  CaptureFromOptions from;
  from.pull = rec;
  const CaptureCheckResult r = CheckRecordings(from, NoRegistration());
  EXPECT_EQ(r.capture, rec);
  EXPECT_EQ(Find(r, "recording drops", "pull recording").status, Status::kOk);
  EXPECT_NEAR(Find(r, "frame rate", "pull").value, 30, 0.01);
  EXPECT_GE(Find(r, "tape markers", "pull frame 0").value, 8) << FormatTable(r);
  EXPECT_EQ(Find(r, "scan views", "scans").status, Status::kFail);
}

TEST(CaptureCheck, BadInputIsAClearError) {
  const fs::path dir = test::TempDir();
  EXPECT_NE(test::ErrorOf<InputError>([&] {
              CheckCapture(dir / "nowhere");
            }).find("nowhere: no such folder"),
            std::string::npos);
  EXPECT_NE(test::ErrorOf<InputError>([&] { CheckCapture(dir); }).find("not a capture folder"),
            std::string::npos);
  CaptureCheckOptions bad;
  bad.thresholds.warn_tape_px = 1;  // below fail_tape_px
  EXPECT_NE(test::ErrorOf<InputError>([&] {
              CheckCapture(QuickCapture(), bad);
            }).find("thresholds.warn_tape_px"),
            std::string::npos);
  CaptureCheckOptions purple;
  purple.tape_color = "purple";
  EXPECT_NE(test::ErrorOf<InputError>([&] {
              CheckCapture(QuickCapture(), purple);
            }).find("--color: expected auto, red"),
            std::string::npos);
}

}  // namespace
}  // namespace simtree::capture_check
