#pragma once
// Draws a tree as it moves: textured generalized-cylinder branches and instanced leaves, both
// skinned on the GPU from the node poses uploaded once per frame (one draw call for the bark, one
// for the leaf blades, one for the petioles), a ground grid, and overlays (markers, ropes).
// Shared by the interactive viewer and the headless renderer; needs a current OpenGL 3.3 core
// context for its whole life.

#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/dynamics/tree_dynamics.h"
#include "simtree/io/image_io.h"
#include "simtree/viewer/detail/camera.h"
#include "simtree/viewer/detail/foliage.h"
#include "simtree/viewer/detail/leaf_model.h"
#include "simtree/viewer/detail/leaf_simplify.h"

namespace simtree::viewer {

enum class BranchColouring {
  kBark,    // the bark texture
  kLevel,   // the colour per level of the meshes simtree writes (io/mesh_io.h)
  kSource,  // material source: measured green, interpolated amber, default grey
};

struct SceneStyle {
  bool leaves = true;
  bool grid = true;
  BranchColouring colouring = BranchColouring::kBark;
  int hovered_branch = -1;   // tinted lightly
  int selected_branch = -1;  // tinted strongly
  Eigen::Vector3f background = {0.78f, 0.85f, 0.92f};
};

struct SceneOptions {
  // The branches' tubes (sides >= 3, min_radius >= 0 m).
  TubeMeshOptions tube = {.sides = 8, .caps = true, .min_radius = 1e-3};
  double bark_metres = 0.6;     // the bark texture repeats along this length of branch (m, > 0)
  double grid_spacing_m = 0.5;  // between the ground grid's lines (m, > 0)
  // The leaf model drawn: simplified to within 1 % of its length (tolerance 0: the authors' mesh).
  // Leaves are a few tens of pixels long in a view of the whole tree, where their triangles are
  // most of a software rasteriser's frame.
  LeafSimplifyOptions leaf_detail;
  int petiole_sides = 3;  // sides of a petiole's tube (>= 3): a petiole is a pixel or two wide

  // Throws InputError ("scene options", the field) for a value out of range.
  void Validate() const;
};

class SceneRenderer {
 public:
  // `foliage` may be null: no leaves, a plain bark colour. `leaves` are where the leaves go.
  // Throws InputError for an empty tree or options out of range (options.Validate()).
  SceneRenderer(const Tree& tree, const LeafAssets* foliage, std::vector<LeafInstance> leaves,
                const SceneOptions& options = {});
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // The pose of every node (TreeDynamics order): uploaded once per frame.
  void SetPose(std::span<const Eigen::Vector3f> positions,
               std::span<const Eigen::Quaternionf> rotations);
  void SetPose(const dynamics::TreeDynamics& sim);
  // The rest pose.
  void SetRestPose();

  // Clears the current framebuffer and draws the scene into a viewport of `camera`'s size whose
  // left edge is `viewport_x` pixels from the framebuffer's (room for a side panel).
  void Draw(const CameraView& camera, const SceneStyle& style, int viewport_x = 0);
  // Overlays on what Draw() drew: round points of `size_px`, and line segments (pairs of points).
  void DrawPoints(const CameraView& camera, std::span<const Eigen::Vector3f> points,
                  const Eigen::Vector4f& colour, float size_px);
  void DrawLines(const CameraView& camera, std::span<const Eigen::Vector3f> endpoints,
                 const Eigen::Vector4f& colour);

  bool has_leaves() const;
  int leaf_count() const;
  // Triangles drawn per frame: branches, plus leaves when `with_leaves`.
  int64_t triangle_count(bool with_leaves) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The colour of the current read framebuffer, top row first (what a screenshot shows).
RgbImage ReadPixels(int width, int height);

}  // namespace simtree::viewer
