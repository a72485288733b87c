#pragma once
// Azure Kinect recordings (the Matroska .mkv that k4arecorder writes), read with FFmpeg's libav
// and no Azure Kinect SDK: the factory calibration of the `calibration.json` attachment, the
// COLOR / DEPTH / IR tracks one capture at a time, the SDK's Brown-Conrady lens model, and depth
// registered into an undistorted (pinhole) colour camera. docs/formats.md says which recorder
// settings are supported.
//
//   AzureKinectReader reader("scan.mkv");                // tracks, calibration, nothing decoded
//   const AzureRegistration reg(reader.calibration());    // maps computed once per recording
//   while (std::optional<AzureCapture> c = reader.Next()) {
//     if (!c->color || !c->depth) continue;               // a frame the camera dropped
//     const RgbdImage rgbd = reg.Apply(*c->color, *c->depth);  // pinhole colour + depth in it
//   }

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/io/image_io.h"

namespace simtree {

// ---------------------------------------------------------------------------------------------
// Calibration

// The Azure Kinect SDK's lens model (Brown-Conrady with a rational radial term): a camera-frame
// point (X, Y, Z) has normalized coordinates (x, y) = (X/Z, Y/Z); around the centre of distortion
// (codx, cody), with r^2 = x'^2 + y'^2,
//   d = (1 + k1 r^2 + k2 r^4 + k3 r^6) / (1 + k4 r^2 + k5 r^4 + k6 r^6)
//   x'' = x' d + (r^2 + 2 x'^2) p2 + 2 x' y' p1,   y'' = y' d + (r^2 + 2 y'^2) p1 + 2 x' y' p2
// and the pixel is (fx x'' + cx, fy y'' + cy), pixel centres at integers (OpenCV convention).
struct BrownConradyCamera {
  int width = 0;
  int height = 0;
  double cx = 0, cy = 0, fx = 0, fy = 0;
  double k1 = 0, k2 = 0, k3 = 0, k4 = 0, k5 = 0, k6 = 0;
  double codx = 0, cody = 0, p1 = 0, p2 = 0;
  // Largest r (normalized) the calibration is valid to; 0 when the file gives none.
  double metric_radius = 0;

  // Undistorted normalized (x, y) -> distorted normalized coordinates.
  Eigen::Vector2d Distort(const Eigen::Vector2d& xy) const;
  // The inverse of Distort (Newton's method); nothing when it does not converge.
  std::optional<Eigen::Vector2d> Undistort(const Eigen::Vector2d& distorted) const;
  // Camera-frame point -> pixel; nothing behind the camera or beyond the metric radius.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& point) const;
  // Pixel -> undistorted normalized (x, y) (the ray through it is (x, y, 1)).
  std::optional<Eigen::Vector2d> PixelRay(double u, double v) const;
  // The pinhole camera of the same size, focal lengths and principal point, without distortion.
  CameraIntrinsics Pinhole() const;
};

// x_target = rotation * x_source + translation (metres).
struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d Apply(const Eigen::Vector3d& p) const { return rotation * p + translation_m; }
  RigidTransform Inverse() const;
};

// The factory calibration for one recording's modes: both cameras at the image sizes recorded.
struct AzureCalibration {
  BrownConradyCamera depth;  // also the IR camera
  BrownConradyCamera color;
  RigidTransform depth_to_color;
  std::string serial;  // CalibrationInformation.Metadata.SerialId, "" when absent
};

// Parses the calibration.json of a recording (the same text the SDK's
// k4a_device_get_raw_calibration gives) and scales it to the recorded image sizes: the depth
// mode is told by its size (640x576 NFOV unbinned, 320x288 NFOV 2x2 binned, 512x512 WFOV 2x2
// binned, 1024x1024 WFOV unbinned or passive IR), the colour resolution by its aspect (16:9 modes
// are the sensor's centre 4096x2304, 4:3 the whole sensor). `source` names the file in errors,
// which name the JSON field that is missing or wrong. A size of 0 skips that camera.
AzureCalibration ParseAzureCalibration(const std::string& json_text, const std::string& source,
                                       int depth_width, int depth_height, int color_width,
                                       int color_height);

// ---------------------------------------------------------------------------------------------
// Reading a recording

struct AzureTrack {
  std::string name;    // "COLOR", "DEPTH", "IR", "IMU"
  std::string codec;   // libav's codec name: "mjpeg", "rawvideo", ...
  std::string fourcc;  // "MJPG", "b16g", "NV12", "YUY2", "BGRA"; "" when none
  std::string mode;    // the track's K4A_*_MODE tag ("MJPG_720P", "NFOV_UNBINNED"), "" when none
  int width = 0;
  int height = 0;
};

struct AzureReaderOptions {
  bool read_color = true;  // decode colour (off: depth-only passes are several times faster)
  bool read_depth = true;
  bool read_ir = false;
  // A colour and a depth frame whose timestamps (after the recording's depth delay) differ by at
  // most this much form one capture. The camera stamps a capture's frames alike, so anything
  // under half a frame period (16 ms at 30 fps) works.
  int64_t pair_tolerance_us = 10000;
  void Validate() const;
};

// One capture: the frames the camera took together. A frame is absent when its track is off,
// not read, or the camera dropped it (then the capture holds the other frames alone).
struct AzureCapture {
  int index = 0;                    // 0, 1, ... in time order
  int64_t timestamp_us = 0;         // recording time of the capture's first frame (microseconds)
  std::optional<RgbImage> color;    // 8-bit RGB, distorted (as the colour camera saw it)
  std::optional<DepthImage> depth;  // millimetres along z of the depth camera, 0 = none
  std::optional<DepthImage> ir;     // raw 16-bit IR counts
  int64_t color_timestamp_us = -1;  // -1 when there is no colour frame
  int64_t depth_timestamp_us = -1;  // -1 when there is no depth frame
};

// What a pass over the recording found; final once Next() has returned nothing.
struct AzureReadStats {
  int captures = 0;
  int color_frames = 0;
  int depth_frames = 0;
  int ir_frames = 0;
  int color_without_depth = 0;  // captures whose depth frame is missing
  int depth_without_color = 0;
  // Frames missing from a track's regular rhythm: sum over gaps of round(gap / period) - 1,
  // with the period the track's median frame interval.
  int dropped_color = 0;
  int dropped_depth = 0;
  double frame_rate_hz = 0;  // 1 / the median interval of the depth (else colour) track
};

// Reads one recording sequentially with bounded memory (one capture and a frame per track in
// flight). Opening reads only the headers and the calibration attachment. Every error is an
// InputError naming the file and, for frames, the track and frame number: an unreadable or
// truncated file, a missing calibration, an unsupported colour format, frames of the wrong size,
// timestamps that go back.
class AzureKinectReader {
 public:
  explicit AzureKinectReader(const std::filesystem::path& path, AzureReaderOptions options = {});
  ~AzureKinectReader();
  AzureKinectReader(const AzureKinectReader&) = delete;
  AzureKinectReader& operator=(const AzureKinectReader&) = delete;

  const std::filesystem::path& path() const;
  const std::vector<AzureTrack>& tracks() const;
  const AzureTrack* FindTrack(const std::string& name) const;
  const AzureCalibration& calibration() const;
  const std::string& calibration_json() const;
  // K4A_DEPTH_DELAY_NS of the recording, in microseconds (depth frames are that much later).
  int64_t depth_delay_us() const;
  // K4A_START_OFFSET_NS in microseconds: a frame's device timestamp is its recording timestamp
  // plus this.
  int64_t start_offset_us() const;

  // The next capture in time order; nothing at the end of the recording.
  std::optional<AzureCapture> Next();
  const AzureReadStats& stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------------------------------------
// Writing recordings of the same layout (tests; later `capture-export`)

enum class AzureColorFormat { kMjpeg, kNv12, kYuy2, kBgra };

struct AzureWriterOptions {
  AzureColorFormat color_format = AzureColorFormat::kMjpeg;
  int color_width = 0;  // 0: no COLOR track
  int color_height = 0;
  int depth_width = 0;  // 0: no DEPTH track
  int depth_height = 0;
  bool ir = false;               // an IR track of the depth size
  std::string calibration_json;  // the calibration.json attachment; "" writes none
  int64_t depth_delay_us = 0;    // written as K4A_DEPTH_DELAY_NS
  void Validate() const;
};

// Writes the tracks k4arecorder writes (COLOR as MJPEG or raw NV12/YUY2/BGRA, DEPTH and IR as raw
// b16g, the calibration attachment and the K4A tags) with libavformat's Matroska muxer. Matroska
// as libav writes it keeps millisecond timestamps (k4arecorder keeps microseconds), so timestamps
// are rounded to the millisecond. The file appears at Close(); without it, nothing does.
class AzureKinectWriter {
 public:
  AzureKinectWriter(const std::filesystem::path& path, const AzureWriterOptions& options);
  ~AzureKinectWriter();
  AzureKinectWriter(const AzureKinectWriter&) = delete;
  AzureKinectWriter& operator=(const AzureKinectWriter&) = delete;

  // The capture's frames at their own timestamps (color_timestamp_us, depth_timestamp_us; IR at
  // the depth's). Timestamps must increase per track.
  void Write(const AzureCapture& capture);
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------------------------------------
// Undistortion and registration

struct AzureRegistrationOptions {
  // A depth pixel is splatted over the colour pixels its footprint covers, up to this many on a
  // side (a grazing surface's footprint is long and thin; larger ones are clipped to it).
  int max_splat_pixels = 6;
  // Each footprint grows by this much (colour pixels) on every side: neighbouring depth pixels
  // at slightly different (noisy) depths project to footprints that no longer meet exactly, and
  // would leave single-pixel holes in rings where their edges pass through pixel centres.
  double splat_margin_px = 0.3;
  void Validate() const;
};

// The colour camera made a pinhole camera (CameraIntrinsics: same size, focal lengths and
// principal point, no distortion), and depth registered into it: each depth pixel unprojected
// through the depth lens model, moved by the depth-to-colour extrinsics, projected into the pinhole
// colour camera and splatted over its footprint with a z-buffer (the nearest surface wins), so
// every colour pixel of a surface the depth camera saw gets that surface's depth (z in the colour
// camera, millimetres). The per-pixel rays are computed once here.
class AzureRegistration {
 public:
  explicit AzureRegistration(const AzureCalibration& calibration,
                             AzureRegistrationOptions options = {});

  const CameraIntrinsics& color_pinhole() const { return pinhole_; }
  // The colour image resampled (bilinear) into the pinhole camera; black where no source pixel.
  RgbImage UndistortColor(const RgbImage& color) const;
  // Depth (of the depth camera's size) in the pinhole colour camera.
  DepthImage RegisterDepth(const DepthImage& depth) const;
  // Both, as an RgbdImage of the pinhole colour camera.
  RgbdImage Apply(const RgbImage& color, const DepthImage& depth) const;
  // The reverse: each depth pixel's colour (depth camera's size), sampled (bilinear) where its
  // point projects into the distorted colour image; black where there is no depth, the point is
  // outside the colour image, or the colour camera sees a nearer surface there (more than 2%
  // nearer: the point is hidden from it).
  RgbImage ColorInDepth(const RgbImage& color, const DepthImage& depth) const;

 private:
  AzureCalibration calibration_;
  AzureRegistrationOptions options_;
  CameraIntrinsics pinhole_;
  // Per pinhole pixel, its bilinear source in the distorted image: the top-left tap's pixel
  // index (-1: none) and the weights of the right and lower taps.
  struct Tap {
    int32_t index = -1;
    float ax = 0;
    float ay = 0;
  };
  static std::vector<Tap> ColorTaps(const BrownConradyCamera& camera);
  std::vector<Tap> color_taps_;
  // Per depth pixel corner ((w+1) x (h+1)): its ray in the colour camera's axes (x, y, z).
  std::vector<float> depth_rays_;
};

}  // namespace simtree
