#pragma once
// Small trees and leaf folders for the viewer tests.

#include <filesystem>
#include <string>

#include "core/tree_fixtures.h"
#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/tree.h"
#include "test_util.h"

namespace simtree::test {

// The core tests' small tree with materials: a vertical trunk (1 m), two children at its middle
// node, a grandchild on the first; branches 2 and 3 are terminal.
inline Tree ViewerTree() { return SmallTreeWithMaterials(); }

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
