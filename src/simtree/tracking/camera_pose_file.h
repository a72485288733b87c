#pragma once
// The pull camera's pose, from either file that holds one: what `simtree register --pull-camera`
// (and `simtree run`, register/pull_camera.json) writes, `simtree.pull_camera` with its
// `frame_from_camera` in the registration frame, or synth's gt/pull_camera.json,
// {"world_from_camera": [16 numbers]}. Either way the pose takes camera-frame points (OpenCV:
// x right, y down, z forward) into the frame of the tree it goes with.
//
//   const Eigen::Isometry3d tree_from_camera = ReadCameraPoseJson("register/pull_camera.json");

#include <filesystem>

#include <Eigen/Geometry>

namespace simtree::tracking {

// Throws InputError naming the file and field: a missing file, neither shape, a pose that is not
// 16 numbers of a rigid transform, or a pull_camera.json whose camera was not placed.
Eigen::Isometry3d ReadCameraPoseJson(const std::filesystem::path& path);

}  // namespace simtree::tracking
