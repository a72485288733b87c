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

// URDF and SDF joints have one axis each, so a segment's hinges are joined by links of their
// own; these carry next to nothing (some simulators refuse a link without mass, and SDF gives
// one without <inertial> 1 kg).
constexpr double kHingeLinkMass = 1e-6;     // kg
constexpr double kHingeLinkInertia = 1e-9;  // kg m^2, about every axis

}  // namespace simtree::robots::detail
