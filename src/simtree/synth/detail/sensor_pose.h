#pragma once
// Camera poses for the virtual sensor: world_from_camera with OpenCV camera axes (x right, y down,
// z forward), as io/ground_truth.h stores them. Poses are made by camera_rig.h (LookAt).

#include <string>

#include <Eigen/Geometry>

namespace simtree::synth {

// Throws InputError naming `source` unless the pose is finite with an orthonormal, right-handed
// rotation (within 1e-6) and a last row 0 0 0 1.
void ValidateCameraPose(const Eigen::Isometry3d& world_from_camera, const std::string& source);

}  // namespace simtree::synth
