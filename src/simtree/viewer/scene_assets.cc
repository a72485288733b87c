#include "simtree/viewer/scene_assets.h"

#include <spdlog/spdlog.h>

#include "simtree/core/error.h"

namespace simtree::viewer {

std::filesystem::path ResolveLeafFolder(const std::string& leaves,
                                        const std::filesystem::path& tree_path) {
  if (leaves == "none" || leaves.empty()) return {};
  if (leaves != "auto") return leaves;
  const std::filesystem::path guess =
      std::filesystem::absolute(tree_path).parent_path().parent_path() / "leaf_model" /
      "apple_leaf";
  return std::filesystem::is_directory(guess) ? guess : std::filesystem::path();
}

SceneAssets LoadSceneAssets(const Tree& tree, const std::filesystem::path& tree_path,
                            const FoliageSource& source) {
  SceneAssets assets;
  const std::filesystem::path folder = ResolveLeafFolder(source.leaves, tree_path);
  if (folder.empty()) return assets;
  try {
    assets.foliage = LoadLeafAssets(folder);
  } catch (const Error& e) {
    assets.error = e.what();
    spdlog::error("leaves: {}; going on without leaves", e.what());
    return assets;
  }
  assets.leaves = PlaceLeaves(tree, assets.foliage->model.Length(), source.placement);
  spdlog::info("leaves: {} {} leaves on the terminal branches", assets.leaves.size(),
               assets.foliage->name);
  return assets;
}

}  // namespace simtree::viewer
