#pragma once
// The layouts capture-from reads, told apart by the path: a .mkv (Azure Kinect, io/azure_kinect.h),
// a folder with rgb.txt and depth.txt (TUM RGB-D, io/tum_rgbd.h), a folder with depth/, color/
// and intrinsic.json (Open3D, io/open3d_folder.h); and the options that open any non-.mkv one as
// an RgbdSequence.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "simtree/io/rgbd_sequence.h"

namespace simtree {

enum class RecordingLayout { kAuto, kAzureMkv, kTumRgbd, kOpen3dFolder, kRealSenseBag };

// "auto", "mkv", "tum", "open3d", "bag".
std::string LayoutName(RecordingLayout layout);
// Throws OptionError for an unknown name.
RecordingLayout ParseLayout(const std::string& name);
// The layout of `path`; throws InputError saying what each layout looks like when none fits.
RecordingLayout DetectLayout(const std::filesystem::path& path);

// How to open a TUM, Open3D or RealSense recording; unset values take the layout's own.
struct RgbdSequenceOptions {
  std::optional<CameraIntrinsics> intrinsics;  // required for TUM; overrides Open3D's file
  std::optional<double> depth_units_per_m;     // TUM 5000, Open3D 1000, a bag's Depth Units
  double max_time_difference_s = 0.02;         // TUM and bag colour-depth pairing tolerance
  double fps = 30;                             // Open3D folders have no times
  void Validate() const;
};

// `layout` kAuto detects it; kAzureMkv is refused (read .mkv files with AzureKinectReader).
std::unique_ptr<RgbdSequence> OpenRgbdSequence(const std::filesystem::path& path,
                                               RecordingLayout layout,
                                               const RgbdSequenceOptions& options);

}  // namespace simtree
