#include "simtree/viewer/detail/shaders.h"

namespace simtree::shaders {

// Shared by the skinned shaders: the node's pose and the quaternion rotation.
#define SIMTREE_SKINNING                                                  \
  "uniform samplerBuffer u_nodes;\n"                                      \
  "vec3 Rotate(vec4 q, vec3 v) {\n"                                       \
  "  return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v);\n"         \
  "}\n"                                                                   \
  "vec3 NodePosition(int n) { return texelFetch(u_nodes, 2 * n).xyz; }\n" \
  "vec4 NodeRotation(int n) { return texelFetch(u_nodes, 2 * n + 1); }\n"

#define SIMTREE_LIGHTING                                  \
  "uniform vec3 u_light_dir;\n"                           \
  "vec3 Shade(vec3 albedo, vec3 n) {\n"                   \
  "  float key = max(dot(n, u_light_dir), 0.0);\n"        \
  "  float sky = 0.5 + 0.5 * n.z;\n"                      \
  "  return albedo * (0.30 + 0.25 * sky + 0.65 * key);\n" \
  "}\n"

const char* const kBranchVertex =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_offset;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in vec2 a_uv;\n"
    "layout(location = 3) in int a_node;\n"
    "layout(location = 4) in int a_branch;\n" SIMTREE_SKINNING
    "uniform samplerBuffer u_branch_tint;\n"
    "uniform mat4 u_view_projection;\n"
    "out vec3 v_normal;\n"
    "out vec2 v_uv;\n"
    "out vec4 v_tint;\n"
    "void main() {\n"
    "  vec4 q = NodeRotation(a_node);\n"
    "  vec3 world = NodePosition(a_node) + Rotate(q, a_offset);\n"
    "  v_normal = Rotate(q, a_normal);\n"
    "  v_uv = a_uv;\n"
    "  v_tint = texelFetch(u_branch_tint, a_branch);\n"
    "  gl_Position = u_view_projection * vec4(world, 1.0);\n"
    "}\n";

const char* const kBranchFragment =
    "#version 330 core\n"
    "in vec3 v_normal;\n"
    "in vec2 v_uv;\n"
    "in vec4 v_tint;\n"
    "uniform sampler2D u_bark;\n"
    "uniform float u_bark_metres;\n" SIMTREE_LIGHTING
    "out vec4 colour;\n"
    "void main() {\n"
    "  vec3 bark = texture(u_bark, vec2(v_uv.x, v_uv.y / u_bark_metres)).rgb;\n"
    "  vec3 albedo = mix(bark, v_tint.rgb, v_tint.a);\n"
    "  colour = vec4(Shade(albedo, normalize(v_normal)), 1.0);\n"
    "}\n";

const char* const kLeafVertex =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_position;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in vec2 a_uv;\n"
    "layout(location = 3) in int a_node;\n"
    "layout(location = 4) in vec4 a_offset_scale;\n"
    "layout(location = 5) in vec4 a_orientation;\n" SIMTREE_SKINNING
    "uniform mat4 u_view_projection;\n"
    "out vec3 v_normal;\n"
    "out vec2 v_uv;\n"
    "void main() {\n"
    "  vec4 q = NodeRotation(a_node);\n"
    "  vec3 local = a_offset_scale.xyz + Rotate(a_orientation, a_offset_scale.w * a_position);\n"
    "  vec3 world = NodePosition(a_node) + Rotate(q, local);\n"
    "  v_normal = Rotate(q, Rotate(a_orientation, a_normal));\n"
    "  v_uv = a_uv;\n"
    "  gl_Position = u_view_projection * vec4(world, 1.0);\n"
    "}\n";

const char* const kLeafFragment =
    "#version 330 core\n"
    "in vec3 v_normal;\n"
    "in vec2 v_uv;\n"
    "uniform sampler2D u_top;\n"
    "uniform sampler2D u_bottom;\n" SIMTREE_LIGHTING
    "out vec4 colour;\n"
    "void main() {\n"
    "  vec3 n = normalize(v_normal);\n"
    "  vec3 albedo = gl_FrontFacing ? texture(u_top, v_uv).rgb : texture(u_bottom, v_uv).rgb;\n"
    "  colour = vec4(Shade(albedo, gl_FrontFacing ? n : -n), 1.0);\n"
    "}\n";

const char* const kFlatVertex =
    "#version 330 core\n"
    "layout(location = 0) in vec3 a_position;\n"
    "uniform mat4 u_view_projection;\n"
    "uniform float u_point_size;\n"
    "void main() {\n"
    "  gl_Position = u_view_projection * vec4(a_position, 1.0);\n"
    "  gl_PointSize = u_point_size;\n"
    "}\n";

const char* const kFlatFragment =
    "#version 330 core\n"
    "uniform vec4 u_colour;\n"
    "uniform bool u_round;\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "  if (u_round && length(gl_PointCoord - vec2(0.5)) > 0.5) discard;\n"
    "  colour = u_colour;\n"
    "}\n";

#undef SIMTREE_SKINNING
#undef SIMTREE_LIGHTING

}  // namespace simtree::shaders
