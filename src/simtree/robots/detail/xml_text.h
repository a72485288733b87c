#pragma once
// Small helpers shared by the XML writers: numbers at full precision, vectors, rotations.

#include <string>

#include <Eigen/Core>

namespace simtree::robots::detail {

std::string Num(double value);                  // shortest form that reads back the same
std::string Vec(const Eigen::Vector3d& value);  // "x y z"
// Roll, pitch, yaw (URDF/SDF order: R = Rz(yaw) Ry(pitch) Rx(roll)) of the rotation that takes
// +Z onto `direction`.
Eigen::Vector3d RpyFromZTo(const Eigen::Vector3d& direction);

}  // namespace simtree::robots::detail
