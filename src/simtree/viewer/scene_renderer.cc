#include "simtree/viewer/scene_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/io/mesh_io.h"
#include "simtree/viewer/detail/gl_objects.h"
#include "simtree/viewer/detail/shaders.h"

namespace simtree::viewer {
namespace {

struct BranchVertex {
  float offset[3];  // rest position minus the rest position of its node
  float normal[3];
  float uv[2];
  int32_t node;
  int32_t branch;
};

struct LeafVertex {
  float position[3];
  float normal[3];
  float uv[2];
};

struct LeafInstanceData {
  int32_t node;
  float offset_scale[4];
  float orientation[4];  // x, y, z, w
};

// Attribute helpers for the interleaved vertex structs above.
void FloatAttribute(GLuint index, int size, GLsizei stride, size_t offset, GLuint divisor = 0) {
  glEnableVertexAttribArray(index);
  glVertexAttribPointer(index, size, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(index, divisor);
}
void IntAttribute(GLuint index, GLsizei stride, size_t offset, GLuint divisor = 0) {
  glEnableVertexAttribArray(index);
  glVertexAttribIPointer(index, 1, GL_INT, stride, reinterpret_cast<const void*>(offset));
  glVertexAttribDivisor(index, divisor);
}

template <typename T>
void Upload(GLenum target, const gl::Buffer& buffer, const std::vector<T>& data, GLenum usage) {
  glBindBuffer(target, buffer.id());
  glBufferData(target, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data(), usage);
}

// A mesh drawn with one call: its vertex array, index count and textures.
struct Part {
  gl::VertexArray vao;
  gl::Buffer vertices, indices;
  GLsizei index_count = 0;
};

gl::Texture SolidTexture(uint8_t r, uint8_t g, uint8_t b) {
  RgbImage image(2, 2);
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    image.pixels[3 * i] = r;
    image.pixels[3 * i + 1] = g;
    image.pixels[3 * i + 2] = b;
  }
  return gl::MakeImageTexture(image);
}

// Per-vertex normals of the leaf blade: the area-weighted mean of its faces'.
std::vector<Eigen::Vector3f> BladeNormals(const LeafModel& model) {
  std::vector<Eigen::Vector3f> normals(model.vertices.size(), Eigen::Vector3f::Zero());
  for (const Eigen::Vector3i& t : model.triangles) {
    const Eigen::Vector3f n = (model.vertices[t[1]] - model.vertices[t[0]])
                                  .cross(model.vertices[t[2]] - model.vertices[t[0]]);
    for (int k = 0; k < 3; ++k) normals[t[k]] += n;
  }
  for (Eigen::Vector3f& n : normals) {
    n = n.norm() > 1e-12f ? Eigen::Vector3f(n.normalized()) : Eigen::Vector3f::UnitZ();
  }
  return normals;
}

}  // namespace

struct SceneRenderer::Impl {
  Tree tree;
  SceneOptions options;
  int node_count = 0;
  std::vector<Eigen::Vector3f> rest_positions;

  gl::Program branch_program, leaf_program, flat_program;
  Part branches, blade, petiole;
  gl::Buffer leaf_instances;
  int leaf_count = 0;
  bool has_leaves = false;
  gl::Texture bark, leaf_top, leaf_bottom, petiole_texture;

  gl::Buffer node_buffer, tint_buffer;
  gl::Texture node_texture, tint_texture;
  std::vector<float> node_data;  // 8 floats per node
  std::vector<float> tint_data;  // 4 floats per branch
  std::vector<Eigen::Quaternionf> rotations;

  gl::VertexArray flat_vao;
  gl::Buffer flat_buffer;
  std::vector<Eigen::Vector3f> grid_lines;

  void BuildBranches();
  void BuildLeaves(const LeafAssets& assets, const std::vector<LeafInstance>& leaves);
  void BuildGrid();
  void UpdateTints(const SceneStyle& style);
  void DrawFlat(const CameraView& camera, std::span<const Eigen::Vector3f> points, GLenum mode,
                const Eigen::Vector4f& colour, float size_px);
};

void SceneRenderer::Impl::BuildBranches() {
  std::vector<BranchVertex> vertices;
  std::vector<uint32_t> indices;
  TriangleMesh mesh;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> radii;
  const int sides = std::max(3, options.tube.sides);
  int first_node = 0;
  for (const Branch& b : tree.branches) {
    mesh.Clear();
    centers.clear();
    radii.clear();
    for (const Node& node : b.nodes) {
      centers.push_back(node.position);
      radii.push_back(node.radius);
    }
    AppendTube(centers, radii, b.frame.u, b.id, options.tube, mesh);
    // AppendTube lays out a ring of sides + 1 vertices per node, then each cap's centre and ring.
    const size_t n = b.nodes.size();
    const size_t ring = static_cast<size_t>(sides) + 1;
    const size_t rings = n * ring;
    if (mesh.vertex_count() != rings + (options.tube.caps ? 2 * ring : 0)) {
      throw Error(fmt::format("scene: unexpected tube layout for branch {}", b.id));
    }
    const auto base = static_cast<uint32_t>(vertices.size());
    for (size_t k = 0; k < mesh.vertex_count(); ++k) {
      const size_t node = k < rings ? k / ring : (k < rings + ring ? 0 : n - 1);
      const Eigen::Vector3f offset = mesh.vertices[k] - b.nodes[node].position.cast<float>();
      BranchVertex v{};
      std::copy(offset.data(), offset.data() + 3, v.offset);
      std::copy(mesh.normals[k].data(), mesh.normals[k].data() + 3, v.normal);
      v.uv[0] = mesh.uvs[k].x();
      v.uv[1] = mesh.uvs[k].y();
      v.node = first_node + static_cast<int32_t>(node);
      v.branch = b.id;
      vertices.push_back(v);
    }
    for (const Eigen::Vector3i& t : mesh.triangles) {
      for (int c = 0; c < 3; ++c) indices.push_back(base + static_cast<uint32_t>(t[c]));
    }
    first_node += static_cast<int>(n);
  }
  branches.vao = gl::MakeVertexArray();
  branches.vertices = gl::MakeBuffer();
  branches.indices = gl::MakeBuffer();
  glBindVertexArray(branches.vao.id());
  Upload(GL_ARRAY_BUFFER, branches.vertices, vertices, GL_STATIC_DRAW);
  Upload(GL_ELEMENT_ARRAY_BUFFER, branches.indices, indices, GL_STATIC_DRAW);
  const auto stride = static_cast<GLsizei>(sizeof(BranchVertex));
  FloatAttribute(0, 3, stride, offsetof(BranchVertex, offset));
  FloatAttribute(1, 3, stride, offsetof(BranchVertex, normal));
  FloatAttribute(2, 2, stride, offsetof(BranchVertex, uv));
  IntAttribute(3, stride, offsetof(BranchVertex, node));
  IntAttribute(4, stride, offsetof(BranchVertex, branch));
  branches.index_count = static_cast<GLsizei>(indices.size());
  glBindVertexArray(0);
}

void SceneRenderer::Impl::BuildLeaves(const LeafAssets& assets,
                                      const std::vector<LeafInstance>& leaves) {
  const LeafModel model = SimplifyLeafModel(assets.model, options.leaf_detail).model;
  // The blade.
  std::vector<LeafVertex> blade_vertices;
  const std::vector<Eigen::Vector3f> normals = BladeNormals(model);
  for (size_t i = 0; i < model.vertices.size(); ++i) {
    LeafVertex v{};
    std::copy(model.vertices[i].data(), model.vertices[i].data() + 3, v.position);
    std::copy(normals[i].data(), normals[i].data() + 3, v.normal);
    // BMP rows are stored bottom-up; the model's v runs up the image.
    v.uv[0] = model.uvs[i].x();
    v.uv[1] = 1.0f - model.uvs[i].y();
    blade_vertices.push_back(v);
  }
  std::vector<uint32_t> blade_indices;
  for (const Eigen::Vector3i& t : model.triangles) {
    for (int c = 0; c < 3; ++c) blade_indices.push_back(static_cast<uint32_t>(t[c]));
  }
  // The petiole: a thin four-sided tube along its polyline.
  std::vector<LeafVertex> petiole_vertices;
  std::vector<uint32_t> petiole_indices;
  if (model.petiole_points.size() >= 2) {
    TriangleMesh tube;
    std::vector<Eigen::Vector3d> centers;
    std::vector<double> radii;
    for (size_t i = 0; i < model.petiole_points.size(); ++i) {
      centers.push_back(model.petiole_points[i].cast<double>());
      radii.push_back(model.petiole_radii[i]);
    }
    AppendTube(centers, radii, Eigen::Vector3d::UnitZ(), 0,
               {.sides = options.petiole_sides, .caps = false, .min_radius = 1e-4}, tube);
    const float length = std::max(1e-6f, tube.uvs.back().y());
    for (size_t i = 0; i < tube.vertex_count(); ++i) {
      LeafVertex v{};
      std::copy(tube.vertices[i].data(), tube.vertices[i].data() + 3, v.position);
      std::copy(tube.normals[i].data(), tube.normals[i].data() + 3, v.normal);
      v.uv[0] = tube.uvs[i].x();
      v.uv[1] = tube.uvs[i].y() / length;
      petiole_vertices.push_back(v);
    }
    for (const Eigen::Vector3i& t : tube.triangles) {
      for (int c = 0; c < 3; ++c) petiole_indices.push_back(static_cast<uint32_t>(t[c]));
    }
  }
  // Instances, shared by blade and petiole.
  std::vector<LeafInstanceData> instances;
  for (const LeafInstance& leaf : leaves) {
    if (leaf.node < 0 || leaf.node >= node_count) {
      throw Error(fmt::format("scene: leaf on node {}, the tree has {}", leaf.node, node_count));
    }
    LeafInstanceData d{};
    d.node = leaf.node;
    d.offset_scale[0] = leaf.offset.x();
    d.offset_scale[1] = leaf.offset.y();
    d.offset_scale[2] = leaf.offset.z();
    d.offset_scale[3] = leaf.scale;
    d.orientation[0] = leaf.orientation.x();
    d.orientation[1] = leaf.orientation.y();
    d.orientation[2] = leaf.orientation.z();
    d.orientation[3] = leaf.orientation.w();
    instances.push_back(d);
  }
  leaf_instances = gl::MakeBuffer();
  Upload(GL_ARRAY_BUFFER, leaf_instances, instances, GL_STATIC_DRAW);
  leaf_count = static_cast<int>(instances.size());

  auto build = [&](Part& part, const std::vector<LeafVertex>& v, const std::vector<uint32_t>& i) {
    part.vao = gl::MakeVertexArray();
    part.vertices = gl::MakeBuffer();
    part.indices = gl::MakeBuffer();
    glBindVertexArray(part.vao.id());
    Upload(GL_ARRAY_BUFFER, part.vertices, v, GL_STATIC_DRAW);
    Upload(GL_ELEMENT_ARRAY_BUFFER, part.indices, i, GL_STATIC_DRAW);
    const auto stride = static_cast<GLsizei>(sizeof(LeafVertex));
    FloatAttribute(0, 3, stride, offsetof(LeafVertex, position));
    FloatAttribute(1, 3, stride, offsetof(LeafVertex, normal));
    FloatAttribute(2, 2, stride, offsetof(LeafVertex, uv));
    glBindBuffer(GL_ARRAY_BUFFER, leaf_instances.id());
    const auto istride = static_cast<GLsizei>(sizeof(LeafInstanceData));
    IntAttribute(3, istride, offsetof(LeafInstanceData, node), 1);
    FloatAttribute(4, 4, istride, offsetof(LeafInstanceData, offset_scale), 1);
    FloatAttribute(5, 4, istride, offsetof(LeafInstanceData, orientation), 1);
    part.index_count = static_cast<GLsizei>(i.size());
    glBindVertexArray(0);
  };
  build(blade, blade_vertices, blade_indices);
  build(petiole, petiole_vertices, petiole_indices);
  leaf_top = gl::MakeImageTexture(assets.top);
  leaf_bottom = gl::MakeImageTexture(assets.bottom);
  petiole_texture = gl::MakeImageTexture(assets.petiole);
  has_leaves = leaf_count > 0;
}

void SceneRenderer::Impl::BuildGrid() {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const double ground = tree.trunk().base().position.z();
  const double spacing = options.grid_spacing_m;
  const double half =
      spacing * std::ceil(std::max({hi.x() - lo.x(), hi.y() - lo.y(), 2.0}) / spacing);
  const Eigen::Vector3d centre(tree.trunk().base().position.x(), tree.trunk().base().position.y(),
                               ground);
  const int lines = static_cast<int>(std::lround(half / spacing));
  for (int i = -lines; i <= lines; ++i) {
    const double d = i * spacing;
    grid_lines.push_back((centre + Eigen::Vector3d(d, -half, 0)).cast<float>());
    grid_lines.push_back((centre + Eigen::Vector3d(d, half, 0)).cast<float>());
    grid_lines.push_back((centre + Eigen::Vector3d(-half, d, 0)).cast<float>());
    grid_lines.push_back((centre + Eigen::Vector3d(half, d, 0)).cast<float>());
  }
}

void SceneRenderer::Impl::UpdateTints(const SceneStyle& style) {
  tint_data.assign(tree.branches.size() * 4, 0.0f);
  for (const Branch& b : tree.branches) {
    Eigen::Vector4f tint(0, 0, 0, 0);
    if (style.colouring == BranchColouring::kLevel) {
      tint.head<3>() = LevelColour(b.level).cast<float>() / 255.0f;
      tint.w() = 1.0f;
    } else if (style.colouring == BranchColouring::kSource) {
      const MaterialSource source = b.material ? b.material->source : MaterialSource::kDefault;
      if (source == MaterialSource::kMeasured) tint << 0.15f, 0.70f, 0.25f, 1.0f;
      if (source == MaterialSource::kInterpolated) tint << 0.95f, 0.65f, 0.10f, 1.0f;
      if (source == MaterialSource::kDefault || source == MaterialSource::kAssumed) {
        tint << 0.55f, 0.55f, 0.55f, 1.0f;
      }
    }
    if (b.id == style.hovered_branch) tint = Eigen::Vector4f(1.0f, 0.95f, 0.3f, 0.45f);
    if (b.id == style.selected_branch) tint = Eigen::Vector4f(1.0f, 0.45f, 0.05f, 0.8f);
    std::copy(tint.data(), tint.data() + 4, tint_data.begin() + 4 * b.id);
  }
  glBindBuffer(GL_TEXTURE_BUFFER, tint_buffer.id());
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(tint_data.size() * sizeof(float)),
               tint_data.data(), GL_DYNAMIC_DRAW);
}

void SceneRenderer::Impl::DrawFlat(const CameraView& camera,
                                   std::span<const Eigen::Vector3f> points, GLenum mode,
                                   const Eigen::Vector4f& colour, float size_px) {
  if (points.empty()) return;
  glUseProgram(flat_program.id());
  const Eigen::Matrix4f vp = (camera.projection * camera.view).cast<float>();
  glUniformMatrix4fv(gl::Uniform(flat_program, "u_view_projection"), 1, GL_FALSE, vp.data());
  glUniform4fv(gl::Uniform(flat_program, "u_colour"), 1, colour.data());
  glUniform1f(gl::Uniform(flat_program, "u_point_size"), size_px);
  glUniform1i(gl::Uniform(flat_program, "u_round"), mode == GL_POINTS ? 1 : 0);
  glBindVertexArray(flat_vao.id());
  glBindBuffer(GL_ARRAY_BUFFER, flat_buffer.id());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(Eigen::Vector3f)),
               points.data(), GL_STREAM_DRAW);
  FloatAttribute(0, 3, sizeof(Eigen::Vector3f), 0);
  glDrawArrays(mode, 0, static_cast<GLsizei>(points.size()));
  glBindVertexArray(0);
}

void SceneOptions::Validate() const {
  const auto check = [](bool ok, const std::string& field, const std::string& message) {
    CheckOption(ok, "scene options", field, message);
  };
  check(tube.sides >= 3, "tube.sides", fmt::format("expected 3 or more sides, got {}", tube.sides));
  check(tube.min_radius >= 0.0 && std::isfinite(tube.min_radius), "tube.min_radius",
        fmt::format("expected a radius >= 0 m, got {}", tube.min_radius));
  check(bark_metres > 0.0 && std::isfinite(bark_metres), "bark_metres",
        fmt::format("expected a length > 0 m, got {}", bark_metres));
  check(grid_spacing_m > 0.0 && std::isfinite(grid_spacing_m), "grid_spacing_m",
        fmt::format("expected a spacing > 0 m, got {}", grid_spacing_m));
  check(petiole_sides >= 3, "petiole_sides",
        fmt::format("expected 3 or more sides, got {}", petiole_sides));
  leaf_detail.Validate();
}

SceneRenderer::SceneRenderer(const Tree& tree, const LeafAssets* foliage,
                             std::vector<LeafInstance> leaves, const SceneOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.Validate();
  Impl& m = *impl_;
  if (tree.empty()) throw InputError("scene", "tree", "expected a tree with branches");
  m.tree = tree;
  m.options = options;
  m.node_count = tree.NodeCount();
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) m.rest_positions.push_back(n.position.cast<float>());
  }
  m.branch_program = gl::LinkProgram("branch", shaders::kBranchVertex, shaders::kBranchFragment);
  m.leaf_program = gl::LinkProgram("leaf", shaders::kLeafVertex, shaders::kLeafFragment);
  m.flat_program = gl::LinkProgram("flat", shaders::kFlatVertex, shaders::kFlatFragment);

  m.node_buffer = gl::MakeBuffer();
  m.node_texture = gl::MakeTexture();
  m.tint_buffer = gl::MakeBuffer();
  m.tint_texture = gl::MakeTexture();
  m.flat_vao = gl::MakeVertexArray();
  m.flat_buffer = gl::MakeBuffer();

  m.BuildBranches();
  if (foliage != nullptr) {
    m.bark = gl::MakeImageTexture(foliage->bark);
    m.BuildLeaves(*foliage, leaves);
  } else {
    m.bark = SolidTexture(110, 84, 60);
  }
  m.BuildGrid();
  SetRestPose();
  m.UpdateTints(SceneStyle{});
  gl::CheckErrors("building the scene");
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::SetPose(std::span<const Eigen::Vector3f> positions,
                            std::span<const Eigen::Quaternionf> rotations) {
  Impl& m = *impl_;
  if (static_cast<int>(positions.size()) != m.node_count ||
      static_cast<int>(rotations.size()) != m.node_count) {
    throw Error(fmt::format("scene: expected {} node poses, got {} positions and {} rotations",
                            m.node_count, positions.size(), rotations.size()));
  }
  m.node_data.resize(static_cast<size_t>(m.node_count) * 8);
  for (int i = 0; i < m.node_count; ++i) {
    float* d = m.node_data.data() + 8 * static_cast<size_t>(i);
    d[0] = positions[i].x();
    d[1] = positions[i].y();
    d[2] = positions[i].z();
    d[3] = 1.0f;
    d[4] = rotations[i].x();
    d[5] = rotations[i].y();
    d[6] = rotations[i].z();
    d[7] = rotations[i].w();
  }
  glBindBuffer(GL_TEXTURE_BUFFER, m.node_buffer.id());
  // Orphan the old storage so the driver need not wait for the frame that reads it.
  const auto bytes = static_cast<GLsizeiptr>(m.node_data.size() * sizeof(float));
  glBufferData(GL_TEXTURE_BUFFER, bytes, nullptr, GL_STREAM_DRAW);
  glBufferSubData(GL_TEXTURE_BUFFER, 0, bytes, m.node_data.data());
}

void SceneRenderer::SetPose(const dynamics::TreeDynamics& sim) {
  impl_->rotations.resize(static_cast<size_t>(sim.node_count()));
  sim.NodeRotations(impl_->rotations);
  SetPose(sim.node_positions(), impl_->rotations);
}

void SceneRenderer::SetRestPose() {
  impl_->rotations.assign(static_cast<size_t>(impl_->node_count), Eigen::Quaternionf::Identity());
  SetPose(impl_->rest_positions, impl_->rotations);
}

void SceneRenderer::Draw(const CameraView& camera, const SceneStyle& style, int viewport_x) {
  Impl& m = *impl_;
  glViewport(viewport_x, 0, camera.width, camera.height);
  glClearColor(style.background.x(), style.background.y(), style.background.z(), 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_PROGRAM_POINT_SIZE);
  m.UpdateTints(style);

  const Eigen::Matrix4f vp = (camera.projection * camera.view).cast<float>();
  const Eigen::Vector3f light = Eigen::Vector3f(0.35f, -0.6f, 0.75f).normalized();

  // Node poses and branch tints as buffer textures on units 0 and 1.
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, m.node_texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, m.node_buffer.id());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, m.tint_texture.id());
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, m.tint_buffer.id());

  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glUseProgram(m.branch_program.id());
  glUniformMatrix4fv(gl::Uniform(m.branch_program, "u_view_projection"), 1, GL_FALSE, vp.data());
  glUniform3fv(gl::Uniform(m.branch_program, "u_light_dir"), 1, light.data());
  glUniform1i(gl::Uniform(m.branch_program, "u_nodes"), 0);
  glUniform1i(gl::Uniform(m.branch_program, "u_branch_tint"), 1);
  glUniform1i(gl::Uniform(m.branch_program, "u_bark"), 2);
  glUniform1f(gl::Uniform(m.branch_program, "u_bark_metres"),
              static_cast<float>(m.options.bark_metres));
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, m.bark.id());
  glBindVertexArray(m.branches.vao.id());
  glDrawElements(GL_TRIANGLES, m.branches.index_count, GL_UNSIGNED_INT, nullptr);
  glDisable(GL_CULL_FACE);

  if (style.leaves && m.has_leaves) {
    glUseProgram(m.leaf_program.id());
    glUniformMatrix4fv(gl::Uniform(m.leaf_program, "u_view_projection"), 1, GL_FALSE, vp.data());
    glUniform3fv(gl::Uniform(m.leaf_program, "u_light_dir"), 1, light.data());
    glUniform1i(gl::Uniform(m.leaf_program, "u_nodes"), 0);
    glUniform1i(gl::Uniform(m.leaf_program, "u_top"), 2);
    glUniform1i(gl::Uniform(m.leaf_program, "u_bottom"), 3);
    auto draw = [&](const Part& part, const gl::Texture& top, const gl::Texture& bottom) {
      if (part.index_count == 0) return;
      glActiveTexture(GL_TEXTURE2);
      glBindTexture(GL_TEXTURE_2D, top.id());
      glActiveTexture(GL_TEXTURE3);
      glBindTexture(GL_TEXTURE_2D, bottom.id());
      glBindVertexArray(part.vao.id());
      glDrawElementsInstanced(GL_TRIANGLES, part.index_count, GL_UNSIGNED_INT, nullptr,
                              m.leaf_count);
    };
    draw(m.blade, m.leaf_top, m.leaf_bottom);
    draw(m.petiole, m.petiole_texture, m.petiole_texture);
  }
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE0);

  if (style.grid) {
    m.DrawFlat(camera, m.grid_lines, GL_LINES, Eigen::Vector4f(0.45f, 0.5f, 0.45f, 1.0f), 1.0f);
  }
}

void SceneRenderer::DrawPoints(const CameraView& camera, std::span<const Eigen::Vector3f> points,
                               const Eigen::Vector4f& colour, float size_px) {
  glDisable(GL_DEPTH_TEST);
  impl_->DrawFlat(camera, points, GL_POINTS, colour, size_px);
  glEnable(GL_DEPTH_TEST);
}

void SceneRenderer::DrawLines(const CameraView& camera, std::span<const Eigen::Vector3f> endpoints,
                              const Eigen::Vector4f& colour) {
  impl_->DrawFlat(camera, endpoints, GL_LINES, colour, 1.0f);
}

bool SceneRenderer::has_leaves() const { return impl_->has_leaves; }
int SceneRenderer::leaf_count() const { return impl_->leaf_count; }

int64_t SceneRenderer::triangle_count(bool with_leaves) const {
  const Impl& m = *impl_;
  int64_t n = m.branches.index_count / 3;
  if (with_leaves && m.has_leaves) {
    n += static_cast<int64_t>(m.leaf_count) * (m.blade.index_count + m.petiole.index_count) / 3;
  }
  return n;
}

RgbImage ReadPixels(int width, int height) {
  RgbImage image(width, height);
  std::vector<uint8_t> rows(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(rows.data() + static_cast<size_t>(height - 1 - y) * row, row,
                image.pixels.data() + static_cast<size_t>(y) * row);
  }
  return image;
}

}  // namespace simtree::viewer
