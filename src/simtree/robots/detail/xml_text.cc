#include "simtree/robots/detail/xml_text.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace simtree::robots::detail {

std::string Num(double value) {
  if (value == 0.0) return "0";  // no "-0"
  return fmt::format("{:.10g}", value);
}

std::string Vec(const Eigen::Vector3d& value) {
  return Num(value.x()) + " " + Num(value.y()) + " " + Num(value.z());
}

Eigen::Vector3d RpyFromZTo(const Eigen::Vector3d& direction) {
  const Eigen::Matrix3d r =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), direction.normalized())
          .toRotationMatrix();
  const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
  const double roll = std::atan2(r(2, 1), r(2, 2));
  const double yaw = std::atan2(r(1, 0), r(0, 0));
  return {roll, pitch, yaw};
}

}  // namespace simtree::robots::detail
