#pragma once
// Open3D reconstruction-system folders (color/, depth/, an intrinsic JSON) for the Open3D folder
// reader's tests and fuzz seeds. Frame i: colour (x * 6, y * 8, i * 50) and depth raw
// 2000 + 3x + y + 100 i, 40x30 pixels.

#include <filesystem>
#include <string>

namespace simtree::test {

constexpr int kOpen3dWidth = 40;
constexpr int kOpen3dHeight = 30;

// Open3D's PinholeCameraIntrinsic JSON of the folder's camera (fx 35, fy 36, cx 19.5, cy 14.5),
// its matrix column-major as Open3D writes it.
std::string Open3dIntrinsicJson();

// Writes `frames` frames and the camera as `intrinsic_name` into `dir`; returns `dir`.
std::filesystem::path WriteOpen3dFolder(const std::filesystem::path& dir, int frames,
                                        const std::string& intrinsic_name);

}  // namespace simtree::test
