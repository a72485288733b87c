// ExportCapture: each view and the pull stream through a virtual Azure Kinect calibration.

#include "simtree/io/capture_export.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

constexpr int kColorSensorWidth = 4096;
constexpr int kColorSensorHeight = 3072;
// WFOV unbinned: the largest depth image, so the depth loses least on the way.
constexpr int kDepthWidth = 1024;
constexpr int kDepthHeight = 1024;

// ModelParameters with no distortion: cx cy fx fy normalized by the sensor, k1..k6, codx, cody,
// p2, p1 zero.
nlohmann::json Camera(const std::string& purpose, int sensor_w, int sensor_h, double cx, double cy,
                      double fx, double fy) {
  std::vector<double> params = {cx, cy, fx, fy, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  return {{"Intrinsics",
           {{"ModelParameterCount", 14},
            {"ModelParameters", params},
            {"ModelType", "CALIBRATION_LensDistortionModelBrownConrady"}}},
          {"Purpose", purpose},
          {"MetricRadius", 0},
          {"Rt", {{"Rotation", {1, 0, 0, 0, 1, 0, 0, 0, 1}}, {"Translation", {0, 0, 0}}}},
          {"SensorWidth", sensor_w},
          {"SensorHeight", sensor_h}};
}

// The virtual depth camera of a colour camera (see the header).
BrownConradyCamera VirtualDepth(const CameraIntrinsics& color) {
  BrownConradyCamera d;
  d.width = kDepthWidth;
  d.height = kDepthHeight;
  d.fx = d.fy = color.fx * kDepthWidth / color.width;
  d.cx = (kDepthWidth - 1) / 2.0;
  d.cy = (kDepthHeight - 1) / 2.0;
  return d;
}

// The capture's depth seen by the virtual depth camera. Both cameras sit at one place and look
// the same way, so this is a resampling without parallax (z is unchanged): each depth pixel takes
// the nearest colour pixel's depth. Splatting would widen near surfaces a second time when
// capture-from registers the depth back.
DepthImage ToDepthCamera(const DepthImage& depth, const CameraIntrinsics& color) {
  const BrownConradyCamera d = VirtualDepth(color);
  DepthImage out(d.width, d.height, 0);
  for (int v = 0; v < d.height; ++v) {
    const int y = static_cast<int>(std::lround((v - d.cy) / d.fy * color.fy + color.cy));
    if (y < 0 || y >= depth.height) continue;
    for (int u = 0; u < d.width; ++u) {
      const int x = static_cast<int>(std::lround((u - d.cx) / d.fx * color.fx + color.cx));
      if (x >= 0 && x < depth.width) out.at(u, v) = depth.at(x, y);
    }
  }
  return out;
}

AzureWriterOptions WriterOptions(const CameraIntrinsics& k, const CaptureExportOptions& o,
                                 const fs::path& intrinsics_file) {
  AzureWriterOptions w;
  w.color_format = o.color_format;
  w.color_width = k.width;
  w.color_height = k.height;
  w.depth_width = kDepthWidth;
  w.depth_height = kDepthHeight;
  w.calibration_json = PinholeAzureCalibrationJson(k, intrinsics_file.string());
  return w;
}

AzureCapture Frame(const RgbdImage& rgbd, int64_t t_us) {
  AzureCapture c;
  c.color = rgbd.color;
  c.depth = ToDepthCamera(rgbd.depth, rgbd.intrinsics);
  c.color_timestamp_us = c.depth_timestamp_us = t_us;
  return c;
}

}  // namespace

std::string PinholeAzureCalibrationJson(const CameraIntrinsics& k, const std::string& source) {
  const bool wide = static_cast<int64_t>(k.width) * 9 == static_cast<int64_t>(k.height) * 16;
  const bool four_three = static_cast<int64_t>(k.width) * 3 == static_cast<int64_t>(k.height) * 4;
  if (!wide && !four_three) {
    throw InputError(source, "width/height",
                     fmt::format("expected an Azure Kinect colour mode's shape (16:9 or 4:3, "
                                 "e.g. synth --color-size 1280x720), got {}x{}",
                                 k.width, k.height));
  }
  const double scale = static_cast<double>(k.width) / kColorSensorWidth;
  const double crop_y = wide ? (kColorSensorHeight - kColorSensorWidth * 9.0 / 16.0) / 2 : 0.0;
  const nlohmann::json color =
      Camera("CALIBRATION_CameraPurposePhotoVideo", kColorSensorWidth, kColorSensorHeight,
             (k.cx + 0.5) / scale / kColorSensorWidth,
             ((k.cy + 0.5) / scale + crop_y) / kColorSensorHeight, k.fx / scale / kColorSensorWidth,
             k.fy / scale / kColorSensorHeight);
  const BrownConradyCamera d = VirtualDepth(k);
  const nlohmann::json depth =
      Camera("CALIBRATION_CameraPurposeDepth", 1024, 1024, (d.cx + 0.5) / 1024, (d.cy + 0.5) / 1024,
             d.fx / 1024, d.fy / 1024);
  const nlohmann::json doc = {
      {"CalibrationInformation",
       {{"Cameras", {depth, color}},
        {"Metadata",
         {{"SerialId", "simtree-capture-export"}, {"Notes", "pinhole, no distortion"}}}}}};
  return doc.dump(1);
}

CaptureExportResult ExportCapture(const Capture& capture, const fs::path& out_dir,
                                  const CaptureExportOptions& options) {
  options.Validate();
  CaptureExportResult result;
  fs::create_directories(out_dir);
  for (const ScanView& view : options.pull_only ? std::vector<ScanView>{} : capture.views) {
    const RgbdImage rgbd = LoadScanView(view);
    const fs::path path = out_dir / (view.name + ".mkv");
    AzureKinectWriter writer(
        path, WriterOptions(view.intrinsics, options, view.directory / "intrinsics.json"));
    writer.Write(Frame(rgbd, 0));
    writer.Close();
    result.scans.push_back(path);
  }
  if (!capture.pull) return result;
  const PullStream& pull = *capture.pull;
  result.pull = out_dir / "pull.mkv";
  AzureKinectWriter writer(
      result.pull, WriterOptions(pull.intrinsics, options, pull.directory / "intrinsics.json"));
  Progress progress("export pull", static_cast<int64_t>(pull.frames.size()), "frames");
  for (size_t i = 0; i < pull.frames.size(); ++i) {
    const int64_t t_us = std::llround(pull.frames[i].time_s * 1e6);
    writer.Write(Frame(LoadPullFrame(pull, i), t_us));
    progress.Advance();
  }
  writer.Close();
  progress.Done();
  result.pull_frames = static_cast<int>(pull.frames.size());
  return result;
}

}  // namespace simtree
