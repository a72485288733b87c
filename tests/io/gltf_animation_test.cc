#include "simtree/io/gltf_animation.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstring>

#include "simtree/core/error.h"
#include "simtree/core/tube_mesh.h"
#include "test_util.h"

namespace simtree {
namespace {

// One tube along +Z from (0,0,0) to (0,0,1), a joint at each end; the top joint swings 0.5 m
// along +X over three frames and turns about Y.
SkinnedAnimation TwoJointTube() {
  SkinnedAnimation a;
  a.name = "test";
  const std::vector<Eigen::Vector3d> centers = {{0, 0, 0}, {0, 0, 0.5}, {0, 0, 1}};
  const std::vector<double> radii = {0.05, 0.04, 0.03};
  AppendTube(centers, radii, Eigen::Vector3d::UnitX(), 0, {.sides = 6}, a.mesh);
  for (const Eigen::Vector3f& v : a.mesh.vertices) {
    const float w = std::clamp(v.z(), 0.f, 1.f);
    a.vertex_joints.push_back({0, 1});
    a.vertex_weights.push_back({1 - w, w});
  }
  a.joint_rest = {{0, 0, 0}, {0, 0, 1}};
  a.joint_names = {"base", "tip"};
  for (int f = 0; f < 3; ++f) {
    a.times.push_back(0.5f * f);
    a.translations.push_back({0, 0, 0});
    a.rotations.push_back(Eigen::Quaternionf::Identity());
    a.translations.push_back({0.25f * f, 0, 1});
    a.rotations.emplace_back(Eigen::AngleAxisf(0.2f * f, Eigen::Vector3f::UnitY()));
  }
  a.point_names = {"marker M0"};
  for (int f = 0; f < 3; ++f) a.point_positions.push_back({0.1f * f, 0.2f, 0.9f});
  return a;
}

tinygltf::Model Load(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = path.extension() == ".glb"
                      ? loader.LoadBinaryFromFile(&model, &err, &warn, path.string())
                      : loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
  EXPECT_TRUE(ok) << err;
  EXPECT_TRUE(err.empty()) << err;
  return model;
}

template <typename T>
std::vector<T> Read(const tinygltf::Model& model, int accessor_index) {
  const tinygltf::Accessor& accessor = model.accessors[accessor_index];
  const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
  const size_t components = tinygltf::GetNumComponentsInType(accessor.type);
  std::vector<T> out(accessor.count * components);
  std::memcpy(out.data(),
              model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset,
              out.size() * sizeof(T));
  return out;
}

TEST(GltfAnimation, BinaryAndTextReadBackWithEveryPart) {
  const auto dir = test::TempDir();
  const SkinnedAnimation a = TwoJointTube();
  for (const char* name : {"a.glb", "a.gltf"}) {
    WriteGltfAnimation(a, dir / name);
    const tinygltf::Model model = Load(dir / name);
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.skins.size(), 1u);
    EXPECT_EQ(model.skins[0].joints.size(), 2u);
    // Root, two joints, the mesh node, the marker root and one marker.
    EXPECT_EQ(model.nodes.size(), 6u);
    ASSERT_EQ(model.animations.size(), 1u);
    const tinygltf::Animation& anim = model.animations[0];
    EXPECT_EQ(anim.channels.size(), 2u * 2 + 1);  // translation + rotation per joint, a marker
    for (const tinygltf::AnimationSampler& s : anim.samplers) {
      EXPECT_EQ(model.accessors[s.input].count, 3u);  // three frames
      EXPECT_EQ(model.accessors[s.output].count, 3u);
    }
    const tinygltf::Primitive& p = model.meshes[0].primitives[0];
    EXPECT_EQ(model.accessors[p.attributes.at("POSITION")].count, a.mesh.vertices.size());
    EXPECT_EQ(model.accessors[p.attributes.at("JOINTS_0")].componentType,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    EXPECT_EQ(model.accessors[p.indices].count, 3 * a.mesh.triangles.size());
    // Y up: the tip joint's rest position (0, 0, 1) becomes (0, 1, 0).
    const int tip = model.skins[0].joints[1];
    ASSERT_EQ(model.nodes[tip].translation.size(), 3u);
    EXPECT_NEAR(model.nodes[tip].translation[1], 1.0, 1e-6);
    // The tip's last translation key: (0.5, 0, 1) -> (0.5, 1, 0).
    for (const tinygltf::AnimationChannel& c : anim.channels) {
      if (c.target_node != tip || c.target_path != "translation") continue;
      const std::vector<float> keys = Read<float>(model, anim.samplers[c.sampler].output);
      EXPECT_NEAR(keys[6], 0.5f, 1e-6);
      EXPECT_NEAR(keys[7], 1.0f, 1e-6);
      EXPECT_NEAR(keys[8], 0.0f, 1e-6);
    }
    // Inverse bind matrix of the tip: translation by -(0, 1, 0).
    const std::vector<float> ibm = Read<float>(model, model.skins[0].inverseBindMatrices);
    EXPECT_NEAR(ibm[16 + 13], -1.0f, 1e-6);
    // Weights are normalised.
    const std::vector<float> w = Read<float>(model, p.attributes.at("WEIGHTS_0"));
    for (size_t v = 0; v < a.mesh.vertices.size(); ++v) {
      EXPECT_NEAR(w[4 * v] + w[4 * v + 1] + w[4 * v + 2] + w[4 * v + 3], 1.0f, 1e-6);
    }
  }
}

TEST(GltfAnimation, InconsistentInputIsRefusedAndWritesNothing) {
  const auto dir = test::TempDir();
  SkinnedAnimation a = TwoJointTube();
  a.translations.pop_back();
  EXPECT_THROW(WriteGltfAnimation(a, dir / "a.glb"), InputError);
  a = TwoJointTube();
  a.times[2] = a.times[1];
  EXPECT_THROW(WriteGltfAnimation(a, dir / "a.glb"), InputError);
  a = TwoJointTube();
  a.vertex_joints[0][1] = 7;
  EXPECT_THROW(WriteGltfAnimation(a, dir / "a.glb"), InputError);
  EXPECT_THROW(WriteGltfAnimation(TwoJointTube(), dir / "a.obj"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace simtree
