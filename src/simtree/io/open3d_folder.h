#pragma once
// Open3D's reconstruction-system dataset folder (what Open3D's RealSense and Azure Kinect
// recorders write): color/ (or image/, rgb/) with 8-bit .jpg or .png, depth/ with 16-bit .png
// (`depth_scale` units per metre, 1000 by default), paired by their order in name order, and the
// camera in intrinsic.json (or camera_intrinsic.json), Open3D's PinholeCameraIntrinsic JSON.
// The files carry no times: frame i is at i / fps.
//
//   const std::unique_ptr<RgbdSequence> seq = OpenOpen3dFolder("dataset/", {});

#include <filesystem>
#include <memory>
#include <optional>

#include "simtree/io/rgbd_sequence.h"

namespace simtree {

struct Open3dFolderOptions {
  std::optional<CameraIntrinsics> intrinsics;  // overrides the folder's intrinsic.json
  double depth_scale = 1000;                   // depth units per metre
  double fps = 30;                             // frame i is at i / fps seconds
  void Validate() const;
};

// True when `folder` has depth/ and a colour folder (color/, image/ or rgb/) beside an
// intrinsic.json or camera_intrinsic.json.
bool IsOpen3dFolder(const std::filesystem::path& folder);

// Throws InputError when a folder is missing or empty, the colour and depth counts differ, or
// there is no camera.
std::unique_ptr<RgbdSequence> OpenOpen3dFolder(const std::filesystem::path& folder,
                                               const Open3dFolderOptions& options);

}  // namespace simtree
