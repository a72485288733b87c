#pragma once
// The authors' leaf models (shared/data/authors-demo/leaf_model/<name>/): a petiole polyline and a
// textured leaf blade (leaf.txt), with the textures the demo draws them with (leafup.bmp,
// leafdown.bmp, petiole.bmp) and the bark of the branches (branch.bmp).
//
// leaf.txt, as read off the files:
//   PetioleVerNum=P LeafVerNum=L LeafFacesNum=F Scale=S
//   P lines  "i x y z radius"   petiole, base (on the twig) to the blade
//   L lines  "i x y z u v"      blade vertices with texture coordinates
//   F lines  "i a b c"          blade triangles (indices into the blade vertices)
// Coordinates are the demo's (Y up; the leaf points along +x, its width along z); simtree turns
// them into a leaf frame with x along the leaf, y across it and z its upper side's normal, and
// multiplies by Scale.

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/image_io.h"

namespace simtree::viewer {

struct LeafModel {
  std::vector<Eigen::Vector3f> petiole_points;  // leaf frame, base to blade
  std::vector<float> petiole_radii;
  std::vector<Eigen::Vector3f> vertices;  // blade, leaf frame
  std::vector<Eigen::Vector2f> uvs;       // per blade vertex, [0, 1]
  std::vector<Eigen::Vector3i> triangles;
  float scale = 1.0f;  // the file's Scale, already applied to the coordinates

  // Distance from the petiole's base to the farthest blade vertex (leaf frame units).
  float Length() const;
};

// Parses leaf.txt text; `source` names it in errors (InputError with the line).
LeafModel ParseLeafModel(const std::string& text, const std::string& source);
LeafModel ReadLeafModel(const std::filesystem::path& path);

// A leaf folder: the model and its textures. Every file is checked; a missing, corrupt or empty
// one is an InputError naming it.
struct LeafAssets {
  std::string name;  // the folder's name, "apple_leaf"
  LeafModel model;
  RgbImage top, bottom, petiole;
  RgbImage bark;  // branch.bmp
};
LeafAssets LoadLeafAssets(const std::filesystem::path& folder);

}  // namespace simtree::viewer
