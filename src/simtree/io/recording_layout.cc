#include "simtree/io/recording_layout.h"

#include <algorithm>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/open3d_folder.h"
#include "simtree/io/realsense_bag.h"
#include "simtree/io/tum_rgbd.h"

namespace simtree {

namespace fs = std::filesystem;

namespace {

constexpr std::pair<RecordingLayout, const char*> kNames[] = {
    {RecordingLayout::kAuto, "auto"},        {RecordingLayout::kAzureMkv, "mkv"},
    {RecordingLayout::kTumRgbd, "tum"},      {RecordingLayout::kOpen3dFolder, "open3d"},
    {RecordingLayout::kRealSenseBag, "bag"},
};

}  // namespace

std::string LayoutName(RecordingLayout layout) {
  for (const auto& [value, name] : kNames) {
    if (value == layout) return name;
  }
  return "unknown";
}

RecordingLayout ParseLayout(const std::string& name) {
  for (const auto& [value, n] : kNames) {
    if (name == n) return value;
  }
  throw OptionError("layout",
                    fmt::format("expected auto, mkv, bag, tum or open3d, got \"{}\"", name));
}

RecordingLayout DetectLayout(const fs::path& path) {
  if (fs::is_directory(path)) {
    if (IsTumRgbdFolder(path)) return RecordingLayout::kTumRgbd;
    if (IsOpen3dFolder(path)) return RecordingLayout::kOpen3dFolder;
  } else if (fs::is_regular_file(path)) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == ".mkv") return RecordingLayout::kAzureMkv;
    if (IsRosBagFile(path)) return RecordingLayout::kRealSenseBag;
  }
  throw InputError(
      path.string(), "",
      "expected a recording: an Azure Kinect .mkv, a RealSense .bag, a TUM RGB-D folder (rgb.txt, "
      "depth.txt) or an Open3D folder (color/, depth/, intrinsic.json)");
}

void RgbdSequenceOptions::Validate() const {
  if (intrinsics) ValidateIntrinsics(*intrinsics, "options: intrinsics");
  if (depth_units_per_m) CheckPositive("depth_units_per_m", *depth_units_per_m);
  CheckNonNegative("max_time_difference_s", max_time_difference_s);
  CheckPositive("fps", fps);
}

std::unique_ptr<RgbdSequence> OpenRgbdSequence(const fs::path& path, RecordingLayout layout,
                                               const RgbdSequenceOptions& options) {
  options.Validate();
  if (layout == RecordingLayout::kAuto) layout = DetectLayout(path);
  switch (layout) {
    case RecordingLayout::kTumRgbd: {
      TumRgbdOptions tum;
      tum.intrinsics = options.intrinsics;
      tum.depth_factor = options.depth_units_per_m.value_or(tum.depth_factor);
      tum.max_time_difference_s = options.max_time_difference_s;
      return OpenTumRgbd(path, tum);
    }
    case RecordingLayout::kOpen3dFolder: {
      Open3dFolderOptions open3d;
      open3d.intrinsics = options.intrinsics;
      open3d.depth_scale = options.depth_units_per_m.value_or(open3d.depth_scale);
      open3d.fps = options.fps;
      return OpenOpen3dFolder(path, open3d);
    }
    case RecordingLayout::kRealSenseBag: {
      RealSenseBagOptions bag;
      if (options.intrinsics) {
        throw InputError(path.string(), "intrinsics",
                         "a .bag carries its camera; expected no intrinsics to be given");
      }
      bag.depth_units_per_m = options.depth_units_per_m;
      bag.max_time_difference_s = options.max_time_difference_s;
      return OpenRealSenseBag(path, bag);
    }
    default:
      throw InputError(
          path.string(), "",
          fmt::format("expected an image-sequence layout, got {}", LayoutName(layout)));
  }
}

}  // namespace simtree
