// The headless renderer for real (EGL on Mesa's software rasteriser here): the tree is in the
// frames, a pull moves it, side by side puts the capture on the left, a corrupt leaf texture
// leaves a tree without leaves, and the frames become a video.

#include "simtree/viewer/render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/io/ground_truth.h"
#include "simtree/viewer/scene_assets.h"
#include "simtree/viewer/video.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

// Pixels far from the sky colour (the tree, not the grid: grid lines are thin and grey-green).
int TreePixels(const RgbImage& image, const SceneStyle& style, int x0 = 0) {
  const Eigen::Vector3f sky = style.background * 255.0f;
  int n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < image.width; ++x) {
      const Eigen::Vector3f c(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
      if ((c - sky).norm() > 90.0f) ++n;
    }
  }
  return n;
}

int ChangedPixels(const RgbImage& a, const RgbImage& b) {
  int n = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d += std::abs(a.pixels[3 * i + c] - b.pixels[3 * i + c]);
    n += d > 60;
  }
  return n;
}

dynamics::SimulationOptions ShortPull() {
  dynamics::SimulationOptions sim;
  sim.duration_s = 0.6;
  sim.fps = 10;
  dynamics::PullSchedule pull;
  pull.rope = {.branch = 1, .arc_length = -1, .anchor = {2, 0, -1}, .force_n = 600};
  pull.hold_s = 0.2;
  pull.release_s = 10;
  sim.pull = pull;
  return sim;
}

TEST(Render, FramesShowTheTreeAndThePullMovesIt) {
  const Tree tree = test::ViewerTree();
  const auto dir = test::TempDir();
  RenderOptions options;
  options.width = 240;
  options.height = 180;
  options.style.grid = false;
  const RenderResult r = RenderSimulation(tree, ShortPull(), nullptr, {}, options, dir / "frames");
  EXPECT_EQ(r.frames, 7);
  EXPECT_EQ(r.width, 240);
  EXPECT_THAT(r.backend, HasSubstr("OpenGL"));
  const RgbImage first = ReadColorImage(dir / "frames" / "000000.png");
  const RgbImage last = ReadColorImage(dir / "frames" / "000006.png");
  EXPECT_GT(TreePixels(first, options.style), 300);
  EXPECT_GT(ChangedPixels(first, last), 30);
  // Nothing pulls: the frames do not change.
  dynamics::SimulationOptions still = ShortPull();
  still.pull.reset();
  RenderSimulation(tree, still, nullptr, {}, options, dir / "still");
  EXPECT_EQ(ChangedPixels(ReadColorImage(dir / "still" / "000000.png"),
                          ReadColorImage(dir / "still" / "000006.png")),
            0);
}

TEST(Render, ACorruptLeafTextureLeavesTheTreeBare) {
  const Tree tree = test::ViewerTree();
  const auto dir = test::TempDir();
  const auto folder = test::CopyAppleLeaf(dir);
  FoliageSource source;
  source.leaves = folder.string();
  const SceneAssets good = LoadSceneAssets(tree, dir / "tree.json", source);
  EXPECT_TRUE(good.error.empty());
  EXPECT_GT(good.leaves.size(), 5u);
  test::WriteText(folder / "petiole.bmp", "garbage");
  const SceneAssets bad = LoadSceneAssets(tree, dir / "tree.json", source);
  EXPECT_THAT(bad.error, HasSubstr("petiole.bmp"));
  EXPECT_EQ(bad.foliage_or_null(), nullptr);
  EXPECT_TRUE(bad.leaves.empty());
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  dynamics::SimulationOptions sim;
  sim.duration_s = 0;
  // With leaves there are more tree pixels than without.
  RenderSimulation(tree, sim, good.foliage_or_null(), good.leaves, options, dir / "leafy");
  RenderSimulation(tree, sim, bad.foliage_or_null(), bad.leaves, options, dir / "bare");
  EXPECT_GT(TreePixels(ReadColorImage(dir / "leafy" / "000000.png"), options.style),
            TreePixels(ReadColorImage(dir / "bare" / "000000.png"), options.style) + 50);
}

TEST(Render, SideBySidePutsTheCaptureOnTheLeft) {
  const Tree tree = test::ViewerTree();
  const auto dir = test::TempDir();
  const auto capture = dir / "capture";
  WriteCaptureInfo({"synthetic test", "", ""}, capture / "capture.json");
  CameraIntrinsics k{.width = 120, .height = 90, .fx = 100, .fy = 100, .cx = 59.5, .cy = 44.5};
  std::filesystem::create_directories(capture / "pull");
  WriteIntrinsicsJson(k, capture / "pull" / "intrinsics.json");
  std::vector<PullFrame> frames;
  for (int i = 0; i < 4; ++i) {
    frames.push_back(WritePullFrame(capture / "pull", i, i / 10.0, RgbImage(120, 90, 200),
                                    DepthImage(120, 90, 1500)));
  }
  WriteFramesCsv(frames, capture / "pull" / "frames.csv");
  // The pull camera 3 m in front of the tree, looking along +Y at its middle.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // camera x = X, y = -Z, z = +Y
  pose.translation() = Eigen::Vector3d(0, -3, 0.8);
  std::filesystem::create_directories(capture / "gt");
  WritePullCamera(pose, capture / "gt" / "pull_camera.json");

  RenderOptions options;
  options.capture = capture;
  const RenderResult r = RenderSimulation(tree, ShortPull(), nullptr, {}, options, dir / "fig15");
  EXPECT_EQ(r.frames, 4);  // the capture's frames and times, not the simulation's
  EXPECT_EQ(r.width, 240);
  EXPECT_EQ(r.height, 90);
  const RgbImage image = ReadColorImage(dir / "fig15" / "000000.png");
  EXPECT_EQ(image.at(10, 10, 0), 200);                    // the capture
  EXPECT_GT(TreePixels(image, options.style, 120), 100);  // the tree, on the right
  // The trunk's base projects where the pull camera sees it.
  const auto base = PinholeView(k, pose).Project(Eigen::Vector3d(0, 0, 0.1));
  ASSERT_TRUE(base.has_value());
  const int bx = 120 + static_cast<int>(base->x()), by = static_cast<int>(base->y());
  const Eigen::Vector3f sky = options.style.background * 255.0f;
  const Eigen::Vector3f c(image.at(bx, by, 0), image.at(bx, by, 1), image.at(bx, by, 2));
  EXPECT_GT((c - sky).norm(), 60.0f);
  // Without the pose there is no camera to draw from.
  std::filesystem::remove(capture / "gt" / "pull_camera.json");
  EXPECT_THROW(RenderSimulation(tree, ShortPull(), nullptr, {}, options, dir / "x"), InputError);
}

TEST(Render, FramesBecomeAVideo) {
  const Tree tree = test::ViewerTree();
  const auto dir = test::TempDir();
  RenderOptions options;
  options.width = 161;  // odd: the encoder pads it
  options.height = 121;
  RenderSimulation(tree, ShortPull(), nullptr, {}, options, dir / "frames");
  EncodeVideo(dir / "frames", dir / "out" / "pull.mp4", {.fps = 10});
  const std::string bytes = test::ReadText(dir / "out" / "pull.mp4");
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp");
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / ".pull.partial.mp4"));
  EXPECT_THROW(EncodeVideo(dir / "nothing", dir / "bad.mp4", {.fps = 10}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.mp4"));
}

TEST(Render, BadOptionsAreRefusedBeforeAnyWork) {
  EXPECT_NO_THROW(RenderOptions{}.Validate());
  const auto field = [](auto change) {
    RenderOptions o;
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](RenderOptions& o) { o.width = 0; }), "width");
  EXPECT_EQ(field([](RenderOptions& o) { o.samples = 17; }), "samples");
  EXPECT_EQ(field([](RenderOptions& o) { o.pitch_rad = NAN; }), "yaw_rad");
  EXPECT_EQ(field([](RenderOptions& o) { o.zoom = 0; }), "zoom");
  EXPECT_EQ(field([](RenderOptions& o) { o.intrinsics = CameraIntrinsics{}; }), "width, height");
  EXPECT_EQ(field([](RenderOptions& o) { o.scene.grid_spacing_m = 0; }), "grid_spacing_m");
  EXPECT_EQ(field([](RenderOptions& o) { o.backend = static_cast<OffscreenBackend>(5); }),
            "backend");
  const auto dir = test::TempDir();
  RenderOptions bad;
  bad.zoom = -1;
  EXPECT_THROW(RenderSimulation(test::ViewerTree(), ShortPull(), nullptr, {}, bad, dir / "frames"),
               InputError);
  dynamics::SimulationOptions no_frames = ShortPull();
  no_frames.fps = 0;
  EXPECT_THROW(RenderSimulation(test::ViewerTree(), no_frames, nullptr, {}, {}, dir / "frames"),
               InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "frames"));
}

}  // namespace
}  // namespace simtree::viewer
