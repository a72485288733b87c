#pragma once
// GLSL 3.30 core sources of the scene. The tree moves by skinning in the vertex shader: every
// vertex rides one node, whose deformed position and rotation (a quaternion) are read from a
// buffer texture uploaded once per frame, two RGBA32F texels per node.

namespace simtree::shaders {

extern const char* const kBranchVertex;
extern const char* const kBranchFragment;
extern const char* const kLeafVertex;
extern const char* const kLeafFragment;
extern const char* const kFlatVertex;    // grid, markers, ropes: world points, one colour
extern const char* const kFlatFragment;  // round points when drawing GL_POINTS

}  // namespace simtree::shaders
