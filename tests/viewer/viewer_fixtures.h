#pragma once
// Small trees and leaf folders for the viewer tests.

#include <filesystem>
#include <string>

#include "simtree/core/frames.h"
#include "simtree/core/tree.h"
#include "test_util.h"

namespace simtree::test {

// A vertical trunk (1 m, 5 nodes) with two side branches at its top node and one twig on the
// first; every branch has a material.
inline Tree ViewerTree() {
  Tree tree;
  tree.metadata.source = "viewer test";
  auto add = [&](int parent, int parent_node, Eigen::Vector3d base, Eigen::Vector3d dir, int count,
                 double step, double r0) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    for (int i = 0; i < count; ++i) {
      b.nodes.push_back({base + dir.normalized() * step * i, r0 * (1.0 - 0.1 * i)});
    }
    tree.branches.push_back(b);
  };
  add(-1, 0, {0, 0, 0}, {0, 0, 1}, 5, 0.25, 0.05);
  add(0, 4, tree.branches[0].nodes[4].position, {1, 0, 1}, 4, 0.2, 0.02);
  add(0, 4, tree.branches[0].nodes[4].position, {-1, 0.3, 1}, 4, 0.2, 0.02);
  add(1, 3, tree.branches[1].nodes[3].position, {1, 0.5, 0.2}, 3, 0.1, 0.01);
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        1.0 + 0.5 * b.level, 0.03, 2000.0 / (1 + b.level), MaterialSource::kMeasured);
  }
  tree.branches[2].material->source = MaterialSource::kInterpolated;
  return tree;
}

// The authors' apple leaf folder.
inline std::filesystem::path AppleLeaf() {
  return SharedData("authors-demo/leaf_model/apple_leaf");
}

// A copy of the apple leaf folder under `dir`, for tests that break one of its files.
inline std::filesystem::path CopyAppleLeaf(const std::filesystem::path& dir) {
  const std::filesystem::path copy = dir / "apple_leaf";
  std::filesystem::create_directories(copy);
  for (const auto& entry : std::filesystem::directory_iterator(AppleLeaf())) {
    std::filesystem::copy_file(entry.path(), copy / entry.path().filename(),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::permissions(
        copy / entry.path().filename(),
        std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  }
  return copy;
}

}  // namespace simtree::test
