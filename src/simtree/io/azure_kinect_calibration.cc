// The calibration.json attachment of an Azure Kinect recording, scaled to the recorded modes.
// The file holds each camera at its full sensor resolution with normalized intrinsics
// (ModelParameters: cx, cy, fx, fy, k1..k6, codx, cody, p2, p1, in units of the sensor's width
// and height) and its pose relative to the depth camera.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "simtree/io/azure_kinect.h"

namespace simtree {
namespace {

constexpr const char* kDepthPurpose = "CALIBRATION_CameraPurposeDepth";
constexpr const char* kColorPurpose = "CALIBRATION_CameraPurposePhotoVideo";
constexpr const char* kBrownConrady = "CALIBRATION_LensDistortionModelBrownConrady";

// One camera of the file, as stored.
struct RawCamera {
  int sensor_width = 0;
  int sensor_height = 0;
  double params[14] = {};
  double metric_radius = 0;
  RigidTransform pose;  // x_camera = pose(x_depth)
};

// How an image mode sits on the sensor: the crop's top-left corner (sensor pixels) and the scale
// from sensor to image pixels.
struct ModeGeometry {
  double crop_x = 0;
  double crop_y = 0;
  double scale = 1;
};

std::vector<double> Numbers(const JsonNode& node, size_t count) {
  node.ExpectArray();
  if (node.size() != count) {
    node.Fail(fmt::format("expected {} numbers, got {}", count, node.size()));
  }
  std::vector<double> out;
  for (const JsonNode& item : node.Items()) out.push_back(item.Number());
  return out;
}

RigidTransform ReadPose(const JsonNode& rt) {
  const std::vector<double> r = Numbers(rt.Field("Rotation"), 9);
  const std::vector<double> t = Numbers(rt.Field("Translation"), 3);
  RigidTransform pose;
  for (int i = 0; i < 9; ++i) pose.rotation(i / 3, i % 3) = r[i];
  pose.translation_m = Eigen::Vector3d(t[0], t[1], t[2]);
  const double orthogonality =
      (pose.rotation * pose.rotation.transpose() - Eigen::Matrix3d::Identity())
          .cwiseAbs()
          .maxCoeff();
  if (orthogonality > 1e-3 || pose.rotation.determinant() < 0) {
    rt.FailAt(Member(rt.at(), "Rotation"), "expected a rotation matrix (orthonormal, det +1)");
  }
  return pose;
}

RawCamera ReadCamera(const JsonNode& camera) {
  RawCamera raw;
  raw.sensor_width = camera.Integer("SensorWidth");
  raw.sensor_height = camera.Integer("SensorHeight");
  if (raw.sensor_width <= 0 || raw.sensor_height <= 0) {
    camera.Fail(fmt::format("expected a positive SensorWidth and SensorHeight, got {}x{}",
                            raw.sensor_width, raw.sensor_height));
  }
  const JsonNode intrinsics = camera.Field("Intrinsics");
  const std::string model = intrinsics.String("ModelType");
  if (model != kBrownConrady) {
    intrinsics.FailAt(Member(intrinsics.at(), "ModelType"),
                      fmt::format("expected {}, got {}", kBrownConrady, model));
  }
  const std::vector<double> p = Numbers(intrinsics.Field("ModelParameters"), 14);
  std::copy(p.begin(), p.end(), raw.params);
  if (!(raw.params[2] > 0 && raw.params[3] > 0)) {
    intrinsics.FailAt(Member(intrinsics.at(), "ModelParameters"),
                      "expected positive focal lengths (elements 2 and 3)");
  }
  raw.metric_radius = camera.Number("MetricRadius");
  raw.pose = ReadPose(camera.Field("Rt"));
  return raw;
}

std::optional<JsonNode> FindCamera(const JsonNode& cameras, const std::string& purpose) {
  for (const JsonNode& camera : cameras.Items()) {
    if (camera.String("Purpose") == purpose) return camera;
  }
  return std::nullopt;
}

// The depth modes, told apart by image size (NFOV modes are a 640x576 window of the 1024x1024
// sensor at (192, 180); binned modes halve it).
ModeGeometry DepthModeGeometry(const RawCamera& raw, int width, int height,
                               const std::string& source) {
  if (raw.sensor_width != 1024 || raw.sensor_height != 1024) {
    throw InputError(
        source, "depth camera SensorWidth/SensorHeight",
        fmt::format("expected 1024x1024, got {}x{}", raw.sensor_width, raw.sensor_height));
  }
  if (width == 640 && height == 576) return {192, 180, 1.0};
  if (width == 320 && height == 288) return {192, 180, 0.5};
  if (width == 512 && height == 512) return {0, 0, 0.5};
  if (width == 1024 && height == 1024) return {0, 0, 1.0};
  throw InputError(source, "DEPTH track",
                   fmt::format("expected a depth mode's size (640x576, 320x288, 512x512 or "
                               "1024x1024), got {}x{}",
                               width, height));
}

// 16:9 colour modes are the sensor's full-width centre band, 4:3 modes the whole sensor.
ModeGeometry ColorModeGeometry(const RawCamera& raw, int width, int height,
                               const std::string& source) {
  const double scale = static_cast<double>(width) / raw.sensor_width;
  if (static_cast<int64_t>(width) * 9 == static_cast<int64_t>(height) * 16) {
    const double band = raw.sensor_width * 9.0 / 16.0;
    return {0, (raw.sensor_height - band) / 2, scale};
  }
  if (static_cast<int64_t>(width) * raw.sensor_height ==
      static_cast<int64_t>(height) * raw.sensor_width) {
    return {0, 0, scale};
  }
  throw InputError(source, "COLOR track",
                   fmt::format("expected a 16:9 or {}:{} colour size, got {}x{}", raw.sensor_width,
                               raw.sensor_height, width, height));
}

BrownConradyCamera ModeCamera(const RawCamera& raw, const ModeGeometry& mode, int width,
                              int height) {
  const double* p = raw.params;
  BrownConradyCamera c;
  c.width = width;
  c.height = height;
  // Normalized -> sensor pixels -> the mode's pixels; -0.5 moves the origin from the first
  // pixel's corner to its centre.
  c.cx = (p[0] * raw.sensor_width - mode.crop_x) * mode.scale - 0.5;
  c.cy = (p[1] * raw.sensor_height - mode.crop_y) * mode.scale - 0.5;
  c.fx = p[2] * raw.sensor_width * mode.scale;
  c.fy = p[3] * raw.sensor_height * mode.scale;
  c.k1 = p[4];
  c.k2 = p[5];
  c.k3 = p[6];
  c.k4 = p[7];
  c.k5 = p[8];
  c.k6 = p[9];
  c.codx = p[10];
  c.cody = p[11];
  c.p2 = p[12];
  c.p1 = p[13];
  c.metric_radius = raw.metric_radius;
  return c;
}

}  // namespace

RigidTransform RigidTransform::Inverse() const {
  RigidTransform out;
  out.rotation = rotation.transpose();
  out.translation_m = -(out.rotation * translation_m);
  return out;
}

AzureCalibration ParseAzureCalibration(const std::string& json_text, const std::string& source,
                                       int depth_width, int depth_height, int color_width,
                                       int color_height) {
  const nlohmann::json value = ParseJson(json_text, source);
  const JsonNode root(value, source);
  const JsonNode info = root.Field("CalibrationInformation");
  const JsonNode cameras = info.Field("Cameras").ExpectArray();
  const std::optional<JsonNode> depth_node = FindCamera(cameras, kDepthPurpose);
  const std::optional<JsonNode> color_node = FindCamera(cameras, kColorPurpose);
  if (!depth_node) cameras.Fail(fmt::format("expected a camera with Purpose {}", kDepthPurpose));
  if (!color_node) cameras.Fail(fmt::format("expected a camera with Purpose {}", kColorPurpose));
  const RawCamera depth = ReadCamera(*depth_node);
  const RawCamera color = ReadCamera(*color_node);

  AzureCalibration out;
  if (depth_width > 0) {
    out.depth = ModeCamera(depth, DepthModeGeometry(depth, depth_width, depth_height, source),
                           depth_width, depth_height);
  }
  if (color_width > 0) {
    out.color = ModeCamera(color, ColorModeGeometry(color, color_width, color_height, source),
                           color_width, color_height);
  }
  // Each pose maps the depth camera's frame to the camera's own.
  out.depth_to_color.rotation = color.pose.rotation * depth.pose.rotation.transpose();
  out.depth_to_color.translation_m =
      color.pose.translation_m - out.depth_to_color.rotation * depth.pose.translation_m;
  if (const auto metadata = info.Find("Metadata")) {
    if (const auto serial = metadata->Find("SerialId")) out.serial = serial->String();
  }
  return out;
}

}  // namespace simtree
