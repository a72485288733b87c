#include "simtree/preprocessing/preprocess.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "support/quick_capture.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::preprocessing {
namespace {

using test::QuickCapture;
fs::path CopyOfCapture() { return test::CopyOfQuickCapture(); }

TEST(CaptureViews, EveryViewOfACaptureIsPreprocessed) {
  const auto views = PreprocessCaptureViews(OpenCapture(QuickCapture()));
  ASSERT_EQ(views.size(), 4u);
  int with_ground = 0;
  for (const auto& view : views) {
    ASSERT_TRUE(view.result) << view.name << ": " << view.failure;
    with_ground += view.result->ground.has_value();
    EXPECT_GT(view.result->cloud.points_.size(), 1000u) << view.name;
  }
  // The quick tree's uneven ground is not one plane from every side: two of its four views find
  // none (up then comes from the trunk). The full-size captures find it in every view.
  EXPECT_GE(with_ground, 2);
}

TEST(CaptureViews, ABadViewIsReportedAndTheOthersGoOn) {
  const fs::path dir = CopyOfCapture();
  // view_01: every depth pixel 0. view_02: intrinsics that do not match its images.
  WritePng(DepthImage(640, 576, 0), dir / "scans" / "view_01" / "depth.png");
  CameraIntrinsics k = ReadIntrinsicsJson(dir / "scans" / "view_02" / "intrinsics.json");
  k.width = 320;
  WriteIntrinsicsJson(k, dir / "scans" / "view_02" / "intrinsics.json");
  const auto views = LoadViews(dir);
  ASSERT_EQ(views.size(), 4u);
  EXPECT_TRUE(views[0].result);
  EXPECT_FALSE(views[1].result);
  EXPECT_NE(views[1].failure.find("every pixel is 0"), std::string::npos) << views[1].failure;
  EXPECT_FALSE(views[2].result);
  EXPECT_NE(views[2].failure.find("intrinsics"), std::string::npos) << views[2].failure;
  EXPECT_TRUE(views[3].result);
}

TEST(CaptureViews, PreprocessFolderRoundTrips) {
  const fs::path out = test::TempDir() / "clean";
  fs::create_directories(out);
  auto views = PreprocessCaptureViews(OpenCapture(QuickCapture()));
  views[1].result.reset();
  views[1].failure = "spoiled for the test";
  WritePreprocessedViews(views, out);
  EXPECT_TRUE(fs::exists(out / "view_00.ply"));
  EXPECT_FALSE(fs::exists(out / "view_01.ply"));
  const auto back = LoadViews(out);
  ASSERT_EQ(back.size(), views.size());
  EXPECT_EQ(back[1].failure, "spoiled for the test");
  ASSERT_TRUE(back[0].result);
  EXPECT_EQ(back[0].result->cloud.points_.size(), views[0].result->cloud.points_.size());
  EXPECT_NEAR((back[0].result->up - views[0].result->up).norm(), 0.0, 1e-9);
  ASSERT_TRUE(back[0].result->ground);
  EXPECT_NEAR(back[0].result->ground->offset, views[0].result->ground->offset, 1e-9);
}

TEST(CaptureViews, AFolderOfNothingIsAnError) {
  const fs::path dir = test::TempDir();
  EXPECT_THROW(LoadViews(dir), InputError);
  EXPECT_THROW(LoadViews(dir / "missing"), InputError);
  test::WriteText(dir / "preprocess.json", "{\"format\": \"something else\"}");
  EXPECT_THROW(LoadViews(dir), InputError);
}

TEST(CaptureViews, ThePullStreamsFirstFrameIsPreprocessedLikeAView) {
  const Capture capture = OpenCapture(QuickCapture());
  const PreprocessedView pull = PreprocessPullFrame(capture);
  EXPECT_EQ(pull.name, "pull_0");
  ASSERT_TRUE(pull.result) << pull.failure;
  EXPECT_GT(pull.result->cloud.points_.size(), 1000u);
  EXPECT_THROW(PreprocessPullFrame(capture, capture.pull->frames.size()), InputError);
  Capture without = capture;
  without.pull.reset();
  EXPECT_THROW(PreprocessPullFrame(without), InputError);
}

TEST(CaptureViews, NonsenseOptionsAreRefusedBeforeTheInputIsRead) {
  PreprocessOptions options;
  options.outlier_std_ratio = 0.0;
  try {
    LoadViews(test::TempDir() / "missing", options);
    FAIL() << "a zero outlier ratio accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "outlier_std_ratio");
  }
}

TEST(CaptureViews, AMissingFieldOfPreprocessJsonIsNamed) {
  const fs::path dir = test::TempDir();
  test::WriteText(dir / "preprocess.json",
                  "{\"format\": \"simtree.preprocess\", \"version\": 1, \"views\": "
                  "[{\"cloud\": null}]}");
  try {
    LoadViews(dir);
    FAIL() << "a view without its fields accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "views[0].name");
  }
}

}  // namespace
}  // namespace simtree::preprocessing
