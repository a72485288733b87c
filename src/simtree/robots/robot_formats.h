#pragma once
// The three robot-description formats a RobotModel prints as (one writer per file):
//  - MJCF (MuJoCo): nested bodies, hinge joints with stiffness, damping and spring references,
//    capsules, sites at markers, grasp points and tips; the step in <option>.
//  - URDF: links and continuous joints, one joint per hinge (massless-looking links of 1e-6 kg
//    between the hinges of one segment); URDF has no joint springs, so stiffness and spring
//    reference go in Gazebo's <gazebo reference="joint"> extension; sites are links on fixed
//    joints; cylinders (URDF has no capsule).
//  - SDF 1.9: the same links and revolute joints, with <spring_stiffness> and
//    <spring_reference> in each joint's <dynamics>; capsules; sites are <frame>s.
// In all three the trunk's base is fixed to the world and every frame is parallel to the world.

#include <string>

#include "simtree/robots/robot_model.h"

namespace simtree::robots {

enum class RobotFormat { kMjcf, kUrdf, kSdf };
const char* ToString(RobotFormat format);  // "mjcf", "urdf", "sdf"
// "mjcf", "urdf", "sdf"; throws InputError naming `where` on anything else.
RobotFormat ParseRobotFormat(const std::string& text, const std::string& where = "--format");

std::string WriteMjcf(const RobotModel& model);
std::string WriteUrdf(const RobotModel& model);
std::string WriteSdf(const RobotModel& model);
std::string WriteRobotFormat(const RobotModel& model, RobotFormat format);

}  // namespace simtree::robots
