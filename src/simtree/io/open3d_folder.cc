#include "simtree/io/open3d_folder.h"

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/intrinsics_file.h"

namespace simtree {

namespace fs = std::filesystem;

namespace {

std::optional<fs::path> ColorFolder(const fs::path& folder) {
  for (const char* name : {"color", "image", "rgb"}) {
    if (fs::is_directory(folder / name)) return folder / name;
  }
  return std::nullopt;
}

std::optional<fs::path> IntrinsicFile(const fs::path& folder) {
  for (const char* name : {"intrinsic.json", "camera_intrinsic.json"}) {
    if (fs::is_regular_file(folder / name)) return folder / name;
  }
  return std::nullopt;
}

// The folder's images with one of `extensions`, in name order.
std::vector<fs::path> Images(const fs::path& folder,
                             std::initializer_list<const char*> extensions) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (!entry.is_regular_file()) continue;
    for (const char* wanted : extensions) {
      if (ext == wanted) files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

void Open3dFolderOptions::Validate() const {
  CheckPositive("depth_scale", depth_scale);
  CheckPositive("fps", fps);
}

bool IsOpen3dFolder(const fs::path& folder) {
  return fs::is_directory(folder / "depth") && ColorFolder(folder).has_value() &&
         IntrinsicFile(folder).has_value();
}

std::unique_ptr<RgbdSequence> OpenOpen3dFolder(const fs::path& folder,
                                               const Open3dFolderOptions& options) {
  options.Validate();
  const std::optional<fs::path> color_folder = ColorFolder(folder);
  if (!color_folder || !fs::is_directory(folder / "depth")) {
    throw InputError(folder.string(), "",
                     "expected an Open3D dataset folder: color/ (or image/, rgb/) and depth/");
  }
  CameraIntrinsics intrinsics;
  if (options.intrinsics) {
    intrinsics = *options.intrinsics;
  } else if (const std::optional<fs::path> file = IntrinsicFile(folder)) {
    intrinsics = ReadOpen3dIntrinsicJson(*file);
  } else {
    throw InputError(folder.string(), "intrinsic.json",
                     "expected the camera (Open3D's PinholeCameraIntrinsic JSON), or give one");
  }
  const std::vector<fs::path> colors = Images(*color_folder, {".jpg", ".jpeg", ".png"});
  const std::vector<fs::path> depths = Images(folder / "depth", {".png"});
  if (colors.empty()) {
    throw InputError(color_folder->string(), "", "expected .jpg or .png images, found none");
  }
  if (colors.size() != depths.size()) {
    throw InputError(folder.string(), "",
                     fmt::format("expected as many depth images as colour images (they pair in "
                                 "name order), got {} in {} and {} in depth/",
                                 colors.size(), color_folder->filename().string(), depths.size()));
  }
  std::vector<RgbdFileFrame> frames;
  for (size_t i = 0; i < colors.size(); ++i) {
    frames.push_back({static_cast<double>(i) / options.fps, colors[i], depths[i]});
  }
  spdlog::info("{}: {} colour-depth pairs, at {} fps", folder.string(), frames.size(), options.fps);
  return std::make_unique<RgbdFileSequence>(folder.string(), "open3d_folder", intrinsics,
                                            options.depth_scale, std::move(frames));
}

}  // namespace simtree
