#include "simtree/viewer/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/image_io.h"

namespace simtree::viewer {
namespace {

// Puts `right` beside `left` (heights may differ: both top-aligned on a black background).
RgbImage SideBySide(const RgbImage& left, const RgbImage& right) {
  RgbImage out(left.width + right.width, std::max(left.height, right.height), 0);
  for (int y = 0; y < left.height; ++y) {
    std::copy_n(&left.at(0, y), static_cast<size_t>(left.width) * 3, &out.at(0, y));
  }
  for (int y = 0; y < right.height; ++y) {
    std::copy_n(&right.at(0, y), static_cast<size_t>(right.width) * 3, &out.at(left.width, y));
  }
  return out;
}

// Draws every frame the simulation records and writes it as a PNG.
class FrameRenderer : public dynamics::FrameRecorder {
 public:
  FrameRenderer(const Tree& tree, const LeafAssets* foliage,
                const std::vector<LeafInstance>& leaves, const RenderOptions& options,
                CameraView camera, const std::optional<PullStream>& pull, std::filesystem::path dir)
      : tree_(tree),
        options_(options),
        camera_(std::move(camera)),
        pull_(pull),
        dir_(std::move(dir)),
        context_({.width = camera_.width,
                  .height = camera_.height,
                  .samples = options.samples,
                  .backend = options.backend}),
        scene_(tree, foliage, leaves, options.scene) {
    spdlog::info("render: {} ({}x{}, {} triangles a frame{})", context_.description(),
                 camera_.width, camera_.height, scene_.triangle_count(options.style.leaves),
                 scene_.has_leaves() && options.style.leaves
                     ? fmt::format(", {} leaves", scene_.leaf_count())
                     : "");
  }

  void Begin(const dynamics::TreeDynamics& sim, int frame_count, double fps) override {
    progress_ = std::make_unique<Progress>("render", frame_count, "frames");
  }

  void Record(int frame, double time_s, const dynamics::TreeDynamics& sim) override {
    const auto start = std::chrono::steady_clock::now();
    context_.Bind();
    scene_.SetPose(sim);
    scene_.Draw(camera_, options_.style);
    if (options_.markers && !tree_.markers.empty()) {
      markers_.clear();
      for (const Marker& m : tree_.markers) {
        markers_.push_back(sim.PointPosition(m.branch, m.arc_length).cast<float>());
      }
      scene_.DrawPoints(camera_, markers_, Eigen::Vector4f(0.9f, 0.1f, 0.1f, 1.0f), 7.0f);
    }
    RgbImage image = context_.Read();
    draw_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (pull_) {
      // The capture frame nearest in time (capture times start at its first frame).
      const double t0 = pull_->frames.front().time_s;
      size_t best = 0;
      for (size_t i = 1; i < pull_->frames.size(); ++i) {
        if (std::abs(pull_->frames[i].time_s - t0 - time_s) <
            std::abs(pull_->frames[best].time_s - t0 - time_s)) {
          best = i;
        }
      }
      image = SideBySide(LoadPullFrame(*pull_, best).color, image);
    }
    WritePng(image, dir_ / fmt::format("{:06d}.png", frame));
    width_ = image.width;
    height_ = image.height;
    ++frames_;
    progress_->Advance();
  }

  void End() override { progress_->Done(); }

  int frames() const { return frames_; }
  int width() const { return width_; }
  int height() const { return height_; }
  double draw_seconds() const { return draw_seconds_; }
  const std::string& backend() const { return context_.description(); }
  int64_t triangles() const { return scene_.triangle_count(options_.style.leaves); }

 private:
  const Tree& tree_;
  const RenderOptions& options_;
  CameraView camera_;
  const std::optional<PullStream>& pull_;
  std::filesystem::path dir_;
  OffscreenContext context_;
  SceneRenderer scene_;
  std::vector<Eigen::Vector3f> markers_;
  std::unique_ptr<Progress> progress_;
  int frames_ = 0, width_ = 0, height_ = 0;
  double draw_seconds_ = 0.0;
};

}  // namespace

RenderResult RenderSimulation(const Tree& tree, dynamics::SimulationOptions simulation,
                              const LeafAssets* foliage, const std::vector<LeafInstance>& leaves,
                              const RenderOptions& options, const std::filesystem::path& out_dir) {
  const auto start = std::chrono::steady_clock::now();
  if (options.width < 1 || options.height < 1) {
    throw InputError(
        "", "--size",
        fmt::format("expected a positive size, got {}x{}", options.width, options.height));
  }
  std::optional<PullStream> pull;
  CameraView camera;
  if (options.capture) {
    const Capture capture = OpenCapture(*options.capture);
    if (!capture.pull || capture.pull->frames.size() < 2) {
      throw InputError(options.capture->string(), "pull",
                       "expected a pull-test stream of at least 2 frames for side by side");
    }
    pull = capture.pull;
    Eigen::Isometry3d pose;
    if (options.world_from_camera) {
      pose = *options.world_from_camera;
    } else {
      const std::filesystem::path gt = *options.capture / "gt" / "pull_camera.json";
      if (!std::filesystem::exists(gt)) {
        throw InputError(options.capture->string(), "gt/pull_camera.json",
                         "missing: give the pull camera's pose with --camera-pose");
      }
      pose = ReadPullCamera(gt);
    }
    camera = PinholeView(pull->intrinsics, pose);
    simulation.fps = pull->FrameRate();
    simulation.duration_s = pull->frames.back().time_s - pull->frames.front().time_s;
  } else if (options.intrinsics) {
    if (!options.world_from_camera) {
      throw InputError("", "--camera-pose", "a calibrated camera needs its pose");
    }
    ValidateIntrinsics(*options.intrinsics, "--intrinsics");
    camera = PinholeView(*options.intrinsics, *options.world_from_camera);
  } else {
    OrbitCamera orbit;
    orbit.yaw_rad = options.yaw_rad;
    orbit.pitch_rad = options.pitch_rad;
    Eigen::Vector3d lo, hi;
    tree.Bounds(&lo, &hi);
    orbit.Frame(lo, hi, static_cast<double>(options.width) / options.height);
    orbit.Zoom(options.zoom);
    camera = orbit.View(options.width, options.height);
  }

  AtomicDirectory folder(out_dir);
  FrameRenderer renderer(tree, foliage, leaves, options, camera, pull, folder.path());
  dynamics::FrameRecorder* recorders[] = {&renderer};
  const dynamics::SimulationResult run = dynamics::RunSimulation(tree, simulation, recorders);
  folder.Commit();

  RenderResult result;
  result.frames = renderer.frames();
  result.width = renderer.width();
  result.height = renderer.height();
  result.backend = renderer.backend();
  result.triangles_per_frame = renderer.triangles();
  result.draw_ms_per_frame =
      result.frames > 0 ? 1000.0 * renderer.draw_seconds() / result.frames : 0.0;
  result.simulated_fps = simulation.fps;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  (void)run;
  return result;
}

}  // namespace simtree::viewer
