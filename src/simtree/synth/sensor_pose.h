#pragma once
// Camera poses for the virtual sensor: world_from_camera with OpenCV camera axes (x right, y down,
// z forward), as io/ground_truth.h stores them.

#include <string>

#include <Eigen/Geometry>

namespace simtree {

// The pose of a camera at `eye` looking at `target`, with image "up" towards `up` (world +Z by
// default). Throws InputError when eye and target coincide or the view is along `up`.
Eigen::Isometry3d LookAtCamera(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                               const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

// Throws InputError naming `source` unless the pose is finite with an orthonormal, right-handed
// rotation (within 1e-6) and a last row 0 0 0 1.
void ValidateCameraPose(const Eigen::Isometry3d& world_from_camera, const std::string& source);

}  // namespace simtree
