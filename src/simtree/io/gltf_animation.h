#pragma once
// A skinned, animated mesh as glTF 2.0 (binary .glb or .gltf with the buffer embedded), the form
// Blender, three.js and game engines play: every vertex follows one or two joints (linear blend
// skinning), and every joint has a translation and a rotation per frame.
//
// simtree's world is Z up; glTF's is Y up. The writer converts once: (x, y, z) -> (x, z, -y) for
// positions, and the same turn for rotations.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/mesh.h"

namespace simtree {

struct SkinnedAnimation {
  std::string name = "animation";
  TriangleMesh mesh;  // rest pose, world frame (Z up)
  // Per vertex: two joints and their weights (summing to 1; a second weight of 0 is unused).
  std::vector<std::array<uint16_t, 2>> vertex_joints;
  std::vector<std::array<float, 2>> vertex_weights;
  // Joints: rest position (world; rest rotation is the identity) and a name.
  std::vector<Eigen::Vector3f> joint_rest;
  std::vector<std::string> joint_names;
  // Frames: time (s, increasing) and, frame by frame, every joint's position and rotation from
  // rest (world frame): joint j of frame f is at [f * joints + j].
  std::vector<float> times;
  std::vector<Eigen::Vector3f> translations;
  std::vector<Eigen::Quaternionf> rotations;
  // Animated points without geometry (markers): names and, frame by frame, positions.
  std::vector<std::string> point_names;
  std::vector<Eigen::Vector3f> point_positions;
  // RGBA base colour of the mesh's material.
  std::array<float, 4> colour = {0.45f, 0.33f, 0.22f, 1.0f};
};

// The most joints one skin can index (JOINTS_0 as unsigned 16-bit).
inline constexpr int kMaxGltfJoints = 65535;

// Writes atomically; .glb gives a binary file, .gltf a JSON file with the buffer embedded as a
// data URI. Throws InputError for inconsistent sizes (naming the field) and IoError when the
// file cannot be written.
void WriteGltfAnimation(const SkinnedAnimation& animation, const std::filesystem::path& path);

}  // namespace simtree
