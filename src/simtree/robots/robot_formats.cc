#include "simtree/robots/robot_formats.h"

#include "simtree/core/error.h"

namespace simtree::robots {

const char* ToString(RobotFormat format) {
  switch (format) {
    case RobotFormat::kMjcf:
      return "mjcf";
    case RobotFormat::kUrdf:
      return "urdf";
    case RobotFormat::kSdf:
      return "sdf";
  }
  return "?";
}

RobotFormat ParseRobotFormat(const std::string& text, const std::string& where) {
  if (text == "mjcf") return RobotFormat::kMjcf;
  if (text == "urdf") return RobotFormat::kUrdf;
  if (text == "sdf") return RobotFormat::kSdf;
  throw InputError(where, "", "expected mjcf, urdf or sdf, got '" + text + "'");
}

std::string WriteRobotFormat(const RobotModel& model, RobotFormat format) {
  switch (format) {
    case RobotFormat::kMjcf:
      return WriteMjcf(model);
    case RobotFormat::kUrdf:
      return WriteUrdf(model);
    case RobotFormat::kSdf:
      return WriteSdf(model);
  }
  return {};
}

}  // namespace simtree::robots
