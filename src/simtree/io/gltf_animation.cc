#include "simtree/io/gltf_animation.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include <fmt/format.h>
#include <tiny_gltf.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace simtree {
namespace {

// Z up -> Y up: (x, y, z) -> (x, z, -y), a proper rotation (-90 degrees about X).
Eigen::Vector3f ToGltf(const Eigen::Vector3f& p) { return {p.x(), p.z(), -p.y()}; }
Eigen::Quaternionf ToGltf(const Eigen::Quaternionf& q) {
  // The vector part turns like a position.
  return Eigen::Quaternionf(q.w(), q.x(), q.z(), -q.y());
}

void Check(bool ok, const std::string& field, const std::string& message) {
  if (!ok) throw InputError("glTF animation", field, message);
}

// Appends raw bytes to the one buffer, 4-byte aligned, and returns a buffer view over them.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

  int View(const void* data, size_t bytes, int target = 0) {
    std::vector<unsigned char>& buffer = model_.buffers[0].data;
    while (buffer.size() % 4 != 0) buffer.push_back(0);
    const size_t offset = buffer.size();
    buffer.resize(offset + bytes);
    if (bytes > 0) std::memcpy(buffer.data() + offset, data, bytes);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    view.target = target;
    model_.bufferViews.push_back(view);
    return static_cast<int>(model_.bufferViews.size()) - 1;
  }

  int Accessor(int view, int component_type, int type, size_t count, std::vector<double> min = {},
               std::vector<double> max = {}) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = std::move(min);
    accessor.maxValues = std::move(max);
    model_.accessors.push_back(accessor);
    return static_cast<int>(model_.accessors.size()) - 1;
  }

 private:
  tinygltf::Model& model_;
};

std::pair<std::vector<double>, std::vector<double>> Bounds(const std::vector<Eigen::Vector3f>& v) {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3f& p : v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (v.empty()) lo = hi = Eigen::Vector3f::Zero();
  return {{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}};
}

void Validate(const SkinnedAnimation& a) {
  const size_t vertices = a.mesh.vertices.size();
  const size_t joints = a.joint_rest.size();
  const size_t frames = a.times.size();
  Check(vertices > 0 && !a.mesh.triangles.empty(), "mesh", "expected a mesh with triangles");
  Check(a.mesh.normals.size() == vertices, "mesh.normals",
        fmt::format("expected {} normals, got {}", vertices, a.mesh.normals.size()));
  Check(a.vertex_joints.size() == vertices && a.vertex_weights.size() == vertices, "vertex_joints",
        fmt::format("expected joints and weights for {} vertices", vertices));
  Check(joints > 0 && joints <= static_cast<size_t>(kMaxGltfJoints), "joint_rest",
        fmt::format("expected 1 to {} joints, got {}", kMaxGltfJoints, joints));
  Check(a.joint_names.empty() || a.joint_names.size() == joints, "joint_names",
        fmt::format("expected {} names, got {}", joints, a.joint_names.size()));
  Check(frames > 0, "times", "expected at least one frame");
  for (size_t f = 1; f < frames; ++f) {
    Check(a.times[f] > a.times[f - 1], "times",
          fmt::format("expected increasing times, got {} after {}", a.times[f], a.times[f - 1]));
  }
  Check(
      a.translations.size() == frames * joints && a.rotations.size() == frames * joints,
      "translations",
      fmt::format("expected {} frames x {} joints of translations and rotations", frames, joints));
  Check(a.point_positions.size() == frames * a.point_names.size(), "point_positions",
        fmt::format("expected {} frames x {} points", frames, a.point_names.size()));
  for (const auto& j : a.vertex_joints) {
    Check(j[0] < joints && j[1] < joints, "vertex_joints",
          fmt::format("expected joint indices below {}", joints));
  }
  for (const auto& t : a.mesh.triangles) {
    Check(t.minCoeff() >= 0 && static_cast<size_t>(t.maxCoeff()) < vertices, "mesh.triangles",
          fmt::format("expected vertex indices below {}", vertices));
  }
}

// The skinned tube mesh (vertices, normals, joints and weights, triangles) and its material, as
// mesh 0 and material 0.
void AddSkinnedMesh(const SkinnedAnimation& a, BufferBuilder& buffer, tinygltf::Model& model) {
  std::vector<Eigen::Vector3f> positions, normals;
  positions.reserve(a.mesh.vertices.size());
  normals.reserve(a.mesh.vertices.size());
  for (size_t i = 0; i < a.mesh.vertices.size(); ++i) {
    positions.push_back(ToGltf(a.mesh.vertices[i]));
    normals.push_back(ToGltf(a.mesh.normals[i]).normalized());
  }
  const auto [lo, hi] = Bounds(positions);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] = buffer.Accessor(
      buffer.View(positions.data(), positions.size() * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size(), lo, hi);
  primitive.attributes["NORMAL"] = buffer.Accessor(
      buffer.View(normals.data(), normals.size() * 12, TINYGLTF_TARGET_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
  std::vector<uint16_t> joint_index;
  std::vector<float> weight;
  joint_index.reserve(4 * a.vertex_joints.size());
  weight.reserve(4 * a.vertex_joints.size());
  for (size_t i = 0; i < a.vertex_joints.size(); ++i) {
    const float w0 = a.vertex_weights[i][0], w1 = a.vertex_weights[i][1];
    const float sum = w0 + w1 > 0 ? w0 + w1 : 1.0f;
    joint_index.insert(joint_index.end(),
                       {a.vertex_joints[i][0], w1 > 0 ? a.vertex_joints[i][1] : uint16_t{0}, 0, 0});
    weight.insert(weight.end(), {w0 / sum, w1 / sum, 0.f, 0.f});
  }
  primitive.attributes["JOINTS_0"] = buffer.Accessor(
      buffer.View(joint_index.data(), joint_index.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, a.vertex_joints.size());
  primitive.attributes["WEIGHTS_0"] =
      buffer.Accessor(buffer.View(weight.data(), weight.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, a.vertex_weights.size());
  std::vector<uint32_t> indices;
  indices.reserve(3 * a.mesh.triangles.size());
  for (const Eigen::Vector3i& t : a.mesh.triangles) {
    indices.insert(indices.end(), {static_cast<uint32_t>(t.x()), static_cast<uint32_t>(t.y()),
                                   static_cast<uint32_t>(t.z())});
  }
  primitive.indices = buffer.Accessor(
      buffer.View(indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
  tinygltf::Material material;
  material.name = "bark";
  material.pbrMetallicRoughness.baseColorFactor = {a.colour[0], a.colour[1], a.colour[2],
                                                   a.colour[3]};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.9;
  model.materials.push_back(material);
  primitive.material = 0;
  tinygltf::Mesh mesh;
  mesh.name = a.name + " mesh";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
}

// Where the nodes are: 0 the skeleton root, 1..joints the joints, then the skinned mesh, then the
// points' root and the points.
struct NodeLayout {
  int mesh_node = 0;
  int points_root = 0;
  int first_point = 0;
};

// The skeleton (joints at their rest positions, with inverse bind matrices), the skin, the mesh
// node and the animated points.
NodeLayout AddNodes(const SkinnedAnimation& a, BufferBuilder& buffer, tinygltf::Model& model) {
  const size_t joints = a.joint_rest.size();
  tinygltf::Node root;
  root.name = a.name + " skeleton";
  model.nodes.push_back(root);
  std::vector<float> inverse_bind;
  inverse_bind.reserve(16 * joints);
  tinygltf::Skin skin;
  skin.name = a.name + " skin";
  skin.skeleton = 0;
  for (size_t j = 0; j < joints; ++j) {
    tinygltf::Node joint;
    joint.name = a.joint_names.empty() ? fmt::format("joint {}", j) : a.joint_names[j];
    const Eigen::Vector3f p = ToGltf(a.joint_rest[j]);
    joint.translation = {p.x(), p.y(), p.z()};
    model.nodes.push_back(joint);
    model.nodes[0].children.push_back(static_cast<int>(j) + 1);
    skin.joints.push_back(static_cast<int>(j) + 1);
    // Column-major inverse of the rest transform (a pure translation).
    inverse_bind.insert(inverse_bind.end(),
                        {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -p.x(), -p.y(), -p.z(), 1});
  }
  skin.inverseBindMatrices =
      buffer.Accessor(buffer.View(inverse_bind.data(), inverse_bind.size() * 4),
                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, joints);
  model.skins.push_back(skin);
  NodeLayout layout;
  tinygltf::Node mesh_node;
  mesh_node.name = a.name;
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  model.nodes.push_back(mesh_node);
  layout.mesh_node = static_cast<int>(model.nodes.size()) - 1;
  tinygltf::Node points_root;
  points_root.name = a.name + " markers";
  model.nodes.push_back(points_root);
  layout.points_root = static_cast<int>(model.nodes.size()) - 1;
  layout.first_point = layout.points_root + 1;
  for (size_t p = 0; p < a.point_names.size(); ++p) {
    tinygltf::Node point;
    point.name = a.point_names[p];
    const Eigen::Vector3f x = ToGltf(a.point_positions[p]);
    point.translation = {x.x(), x.y(), x.z()};
    model.nodes.push_back(point);
    model.nodes[layout.points_root].children.push_back(layout.first_point + static_cast<int>(p));
  }
  return layout;
}

// The animation: one time accessor shared by every sampler; per joint a translation and a
// rotation track, per point a translation track, each a contiguous run of one buffer view.
void AddAnimation(const SkinnedAnimation& a, const NodeLayout& layout, BufferBuilder& buffer,
                  tinygltf::Model& model) {
  const size_t joints = a.joint_rest.size();
  const size_t frames = a.times.size();
  tinygltf::Animation animation;
  animation.name = a.name;
  const int time_accessor = buffer.Accessor(buffer.View(a.times.data(), a.times.size() * 4),
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                                            frames, {a.times.front()}, {a.times.back()});
  std::vector<float> translation_track(3 * frames * joints);
  std::vector<float> rotation_track(4 * frames * joints);
  for (size_t j = 0; j < joints; ++j) {
    Eigen::Quaternionf previous = Eigen::Quaternionf::Identity();
    for (size_t f = 0; f < frames; ++f) {
      const Eigen::Vector3f t = ToGltf(a.translations[f * joints + j]);
      Eigen::Quaternionf q = ToGltf(a.rotations[f * joints + j]).normalized();
      // Keep consecutive keys in one hemisphere so linear interpolation takes the short way.
      if (q.dot(previous) < 0) q.coeffs() = -q.coeffs();
      previous = q;
      std::memcpy(&translation_track[3 * (j * frames + f)], t.data(), 12);
      const float xyzw[4] = {q.x(), q.y(), q.z(), q.w()};
      std::memcpy(&rotation_track[4 * (j * frames + f)], xyzw, 16);
    }
  }
  const int translation_view = buffer.View(translation_track.data(), translation_track.size() * 4);
  const int rotation_view = buffer.View(rotation_track.data(), rotation_track.size() * 4);
  auto add_track = [&](int node, const char* path_name, int accessor) {
    tinygltf::AnimationSampler sampler;
    sampler.input = time_accessor;
    sampler.output = accessor;
    sampler.interpolation = "LINEAR";
    animation.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = static_cast<int>(animation.samplers.size()) - 1;
    channel.target_node = node;
    channel.target_path = path_name;
    animation.channels.push_back(channel);
  };
  for (size_t j = 0; j < joints; ++j) {
    int t = buffer.Accessor(translation_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                            frames);
    model.accessors[t].byteOffset = 12 * j * frames;
    int r =
        buffer.Accessor(rotation_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, frames);
    model.accessors[r].byteOffset = 16 * j * frames;
    add_track(static_cast<int>(j) + 1, "translation", t);
    add_track(static_cast<int>(j) + 1, "rotation", r);
  }
  if (!a.point_names.empty()) {
    std::vector<float> point_track(3 * frames * a.point_names.size());
    for (size_t p = 0; p < a.point_names.size(); ++p) {
      for (size_t f = 0; f < frames; ++f) {
        const Eigen::Vector3f x = ToGltf(a.point_positions[f * a.point_names.size() + p]);
        std::memcpy(&point_track[3 * (p * frames + f)], x.data(), 12);
      }
    }
    const int view = buffer.View(point_track.data(), point_track.size() * 4);
    for (size_t p = 0; p < a.point_names.size(); ++p) {
      int t = buffer.Accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, frames);
      model.accessors[t].byteOffset = 12 * p * frames;
      add_track(layout.first_point + static_cast<int>(p), "translation", t);
    }
  }
  model.animations.push_back(animation);
}

}  // namespace

void WriteGltfAnimation(const SkinnedAnimation& a, const std::filesystem::path& path) {
  Validate(a);
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  Check(ext == ".glb" || ext == ".gltf", "path",
        fmt::format("expected a file ending in .glb or .gltf, got \"{}\"", path.string()));

  // Buffer views and accessors are numbered in the order these add them.
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "simtree";
  BufferBuilder buffer(model);
  AddSkinnedMesh(a, buffer, model);
  const NodeLayout layout = AddNodes(a, buffer, model);
  AddAnimation(a, layout, buffer, model);
  tinygltf::Scene scene;
  scene.name = a.name;
  scene.nodes = {0, layout.mesh_node, layout.points_root};
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  const bool binary = ext == ".glb";
  AtomicFile file(path, /*binary=*/true);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, file.stream(), /*prettyPrint=*/!binary, binary)) {
    throw IoError(fmt::format("{}: could not write the glTF file", path.string()));
  }
  file.Commit();
}

}  // namespace simtree
