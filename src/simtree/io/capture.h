#pragma once
// The capture folder (docs/formats.md, "Capture folder"): what a real RGB-D capture
// or `simtree synth` gives the pipeline.
//
//   capture.json                       format, version, sensor, species, notes
//   scans/view_XX/{color.png, depth.png, intrinsics.json}    multi-view static scans
//   pull/{intrinsics.json, frames.csv, markers.json, color/*.png, depth/*.png}  pull-test stream
//   gt/                                ground truth (synth only; io/ground_truth.h)
//
// Opening a capture reads the small files and checks that every image file exists; images are
// loaded one view or frame at a time (LoadScanView, LoadPullFrame), each checked against its
// intrinsics.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/image_io.h"

namespace simtree {

inline constexpr const char* kCaptureFormat = "simtree.capture";
inline constexpr int kCaptureFormatVersion = 1;
inline constexpr const char* kMarkersFormat = "simtree.markers";
inline constexpr int kMarkersFormatVersion = 1;

// Pinhole intrinsics of a depth image and the colour image registered to it. Pixel (u, v) has
// its centre at integer (u, v) (the OpenCV and Open3D convention), so a camera-frame point
// (x, y, z) projects to (fx x/z + cx, fy y/z + cy). Depth values are z, not ray length.
struct CameraIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  double depth_scale_m = 0.001;  // metres per depth unit (the Azure Kinect gives millimetres)

  Eigen::Vector2d Project(const Eigen::Vector3d& point_camera) const;
  // The camera-frame point at pixel (u, v) with depth z (metres).
  Eigen::Vector3d Unproject(double u, double v, double z) const;
  bool Contains(double u, double v) const {
    return u >= -0.5 && v >= -0.5 && u < width - 0.5 && v < height - 0.5;
  }
  // Horizontal and vertical field of view (radians) across the whole image.
  double HorizontalFov() const;
  double VerticalFov() const;
  bool operator==(const CameraIntrinsics& other) const = default;
};

// Throws InputError (naming `source`) unless sizes are positive, focal lengths positive and all
// numbers finite.
void ValidateIntrinsics(const CameraIntrinsics& intrinsics, const std::string& source);
CameraIntrinsics ReadIntrinsicsJson(const std::filesystem::path& path);
void WriteIntrinsicsJson(const CameraIntrinsics& intrinsics, const std::filesystem::path& path);

// capture.json.
struct CaptureInfo {
  std::string sensor;   // "azure_kinect_nfov_unbinned" or "synthetic ..."
  std::string species;  // may be empty
  std::string notes;
};
CaptureInfo ReadCaptureInfo(const std::filesystem::path& path);
void WriteCaptureInfo(const CaptureInfo& info, const std::filesystem::path& path);

// One marker of markers.json: the links a user writes down when taping a tree (paper Fig. 8).
struct MarkerLink {
  int id = 0;
  std::string label;
  int parent = -1;            // the marker this one links to; -1 for the root (trunk) marker
  std::optional<int> branch;  // branch id in the static tree, when known
  bool operator==(const MarkerLink& other) const = default;
};
// Checks format and version, unique ids, parents that exist, exactly one root and no cycles.
std::vector<MarkerLink> ReadMarkersJson(const std::filesystem::path& path);
void WriteMarkersJson(const std::vector<MarkerLink>& markers, const std::filesystem::path& path);

// A colour image, its registered depth and their intrinsics.
struct RgbdImage {
  RgbImage color;
  DepthImage depth;
  CameraIntrinsics intrinsics;
};

struct ScanView {
  std::string name;                 // "view_00"
  std::filesystem::path directory;  // <capture>/scans/view_00
  CameraIntrinsics intrinsics;
  std::filesystem::path color_path() const { return directory / "color.png"; }
  std::filesystem::path depth_path() const { return directory / "depth.png"; }
};

struct PullFrame {
  int frame = 0;
  double time_s = 0.0;
  std::string color;  // paths relative to pull/, as in frames.csv
  std::string depth;
};

struct PullStream {
  std::filesystem::path directory;  // <capture>/pull
  CameraIntrinsics intrinsics;
  std::vector<PullFrame> frames;
  std::vector<MarkerLink> markers;  // from markers.json; empty when the file is absent
  bool has_markers = false;
  // Mean frame rate over the stream (frames per second), 0 with fewer than two frames.
  double FrameRate() const;
};

struct Capture {
  std::filesystem::path root;
  CaptureInfo info;
  std::vector<ScanView> views;     // sorted by name; empty when there is no scans/
  std::optional<PullStream> pull;  // absent when there is no pull/
};

// Reads capture.json, every view's intrinsics, frames.csv and markers.json, and checks that every
// image they name exists. Throws InputError with the file and what is wrong.
Capture OpenCapture(const std::filesystem::path& root);

// Loads a view's images and checks them: colour and depth of the intrinsics' size, depth not
// all zero.
RgbdImage LoadScanView(const ScanView& view);
RgbdImage LoadPullFrame(const PullStream& pull, size_t index);
// The checks LoadScanView and LoadPullFrame apply; `source` names the folder in errors.
void ValidateRgbd(const RgbdImage& image, const std::string& color_source,
                  const std::string& depth_source);

// frames.csv ("frame,time_s,color,depth"): read with checks (increasing frames and times, files
// present), write as given.
std::vector<PullFrame> ReadFramesCsv(const std::filesystem::path& path);
void WriteFramesCsv(const std::vector<PullFrame>& frames, const std::filesystem::path& path);

// Writers for the pieces of a capture, used by synth and by converters of real recordings.
// Each file appears whole or not at all.
void WriteScanView(const std::filesystem::path& capture_root, const std::string& view_name,
                   const RgbdImage& image, const PngOptions& png = {});
// Writes color/NNNNNN.png and depth/NNNNNN.png under `pull_directory` and returns the frames.csv
// row for them.
PullFrame WritePullFrame(const std::filesystem::path& pull_directory, int frame, double time_s,
                         const RgbImage& color, const DepthImage& depth,
                         const PngOptions& png = {});

}  // namespace simtree
