#include "simtree/viewer/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
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

// What a run is drawn from and, side by side, the capture stream it is shown beside.
struct RenderView {
  CameraView camera;
  std::optional<PullStream> pull;
};

// The capture's pull camera; the run takes the capture's frame rate and duration.
RenderView SideBySideView(const RenderOptions& options, dynamics::SimulationOptions& simulation) {
  const Capture capture = OpenCapture(*options.capture);
  if (!capture.pull || capture.pull->frames.size() < 2) {
    throw InputError(options.capture->string(), "pull",
                     "expected a pull-test stream of at least 2 frames for side by side");
  }
  RenderView view;
  view.pull = capture.pull;
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
  view.camera = PinholeView(view.pull->intrinsics, pose);
  simulation.fps = view.pull->FrameRate();
  simulation.duration_s = view.pull->frames.back().time_s - view.pull->frames.front().time_s;
  return view;
}

// The orbit camera framing the whole tree.
RenderView OrbitView(const Tree& tree, const RenderOptions& options) {
  OrbitCamera orbit;
  orbit.yaw_rad = options.yaw_rad;
  orbit.pitch_rad = options.pitch_rad;
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  orbit.Frame(lo, hi, static_cast<double>(options.width) / options.height);
  orbit.Zoom(options.zoom);
  RenderView view;
  view.camera = orbit.View(options.width, options.height);
  return view;
}

RenderView ChooseView(const Tree& tree, const RenderOptions& options,
                      dynamics::SimulationOptions& simulation) {
  if (options.capture) return SideBySideView(options, simulation);
  if (options.intrinsics) {
    RenderView view;
    view.camera = PinholeView(*options.intrinsics, *options.world_from_camera);
    return view;
  }
  return OrbitView(tree, options);
}

}  // namespace

void RenderOptions::Validate() const {
  const auto check = [](bool ok, const std::string& field, const std::string& message) {
    CheckOption(ok, "render options", field, message);
  };
  ValidateFramebuffer(width, height, samples, "render options");
  check(std::isfinite(yaw_rad) && std::isfinite(pitch_rad), "yaw_rad",
        fmt::format("expected finite angles, got yaw {} and pitch {}", yaw_rad, pitch_rad));
  check(zoom > 0.0 && std::isfinite(zoom), "zoom", fmt::format("expected > 0, got {}", zoom));
  if (intrinsics) {
    ValidateIntrinsics(*intrinsics, "render options: intrinsics");
    check(world_from_camera.has_value(), "world_from_camera", "a calibrated camera needs its pose");
  }
  check(!world_from_camera || world_from_camera->matrix().allFinite(), "world_from_camera",
        "expected a finite pose");
  scene.Validate();
  OffscreenOptions{.backend = backend}.Validate();
}

RenderResult RenderSimulation(const Tree& tree, dynamics::SimulationOptions simulation,
                              const LeafAssets* foliage, const std::vector<LeafInstance>& leaves,
                              const RenderOptions& options, const std::filesystem::path& out_dir) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  const RenderView view = ChooseView(tree, options, simulation);
  dynamics::ValidateSimulation(tree, simulation);

  AtomicDirectory folder(out_dir);
  FrameRenderer renderer(tree, foliage, leaves, options, view.camera, view.pull, folder.path());
  dynamics::FrameRecorder* recorders[] = {&renderer};
  dynamics::RunSimulation(tree, simulation, recorders);
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
  return result;
}

}  // namespace simtree::viewer
