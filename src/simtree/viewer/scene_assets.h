#pragma once
// What the viewer and the renderer load besides the tree: a leaf model with its textures and the
// leaves placed on the tree. A bad leaf model or texture is not fatal: the message says which file
// and what is wrong, and the scene goes on without leaves (and with a plain bark colour).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/viewer/detail/foliage.h"
#include "simtree/viewer/detail/leaf_model.h"

namespace simtree::viewer {

struct FoliageSource {
  // "auto": <tree file's folder>/../leaf_model/apple_leaf when it exists (the authors' data
  // layout), else none; "none"; or a leaf model folder.
  std::string leaves = "auto";
  FoliageOptions placement;
};

struct SceneAssets {
  std::optional<LeafAssets> foliage;
  std::vector<LeafInstance> leaves;
  std::string error;  // why there are no leaves when some were asked for, else empty

  const LeafAssets* foliage_or_null() const { return foliage ? &*foliage : nullptr; }
};

// The leaf folder `source` names for a tree read from `tree_path` (empty: none).
std::filesystem::path ResolveLeafFolder(const std::string& leaves,
                                        const std::filesystem::path& tree_path);

// Loads and places the leaves. Errors in the leaf files are logged (spdlog::error) and kept in
// `error`; the result then has no leaves. Options out of range still throw InputError.
SceneAssets LoadSceneAssets(const Tree& tree, const std::filesystem::path& tree_path,
                            const FoliageSource& source);

}  // namespace simtree::viewer
