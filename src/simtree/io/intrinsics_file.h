#pragma once
// A camera the user names for a recording that does not carry one (TUM RGB-D) or to override the
// one it carries: simtree's intrinsics.json (docs/formats.md) or Open3D's PinholeCameraIntrinsic
// JSON ({"width", "height", "intrinsic_matrix": 9 numbers, column-major}), told apart by their
// fields.

#include <filesystem>

#include "simtree/io/capture.h"

namespace simtree {

// Open3D's PinholeCameraIntrinsic JSON (what `o3d.io.write_pinhole_camera_intrinsic` writes and
// the reconstruction system's intrinsic.json). Throws InputError naming the file and field unless
// the matrix is [fx 0 cx; 0 fy cy; 0 0 1] stored column-major.
CameraIntrinsics ReadOpen3dIntrinsicJson(const std::filesystem::path& path);

// Either format; depth_scale_m stays simtree's 0.001 for an Open3D file (its depth scale is the
// recording's, given apart).
CameraIntrinsics ReadIntrinsicsFile(const std::filesystem::path& path);

}  // namespace simtree
