#pragma once
// What the virtual sensor sees: an Embree 3 scene of a tree's branches as generalized cylinders,
// red tape bands at the tree's markers, a ground plane z = 0, an evergreen hedge around the tree
// beyond the sensor's range, a few objects inside it, optional occluders (posts, shrubs) and an
// optional rope from the tree to an anchor.
//
// Branches are traced as tight triangle tubes (sensor_tree_tubes.h) and every hit is moved onto the
// exact cone frustum of its segment, so depths and normals are the true generalized cylinder's.
// Posts, shrub twigs and the rope are Embree round curves. Static parts are built once; SetPose()
// moves the branches (450 pull frames, so it only rewrites the tubes' vertices and refits their
// bounding volume hierarchy).
//
// A hit tells what it hit: the kind of surface, and for a branch its id, rest arc length, radius,
// angle around the axis and marker id when inside a tape band. Intersect() is thread-safe between
// SetPose()/SetRope() calls.
//
//   SensorScene scene(tree, DefaultSceneOptions(tree, seed));
//   scene.SetPose(pose);                                   // per frame
//   scene.SetRope(RopeSegment{.branch = 3, .arc_length = 0.4, .anchor = {2, 0, 0}});
//   SceneHit hit = scene.Intersect(origin, direction);

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"
#include "simtree/synth/detail/tree_pose.h"

namespace simtree::synth {

enum class SurfaceKind : uint8_t {
  kNone = 0,    // nothing: sky
  kBranch,      // the tree (marker tells a tape band)
  kGround,      // the plane z = 0
  kBackground,  // the hedge and the objects of SceneOptions::boxes
  kRope,
  kOccluder,  // posts and shrubs
};
const char* ToString(SurfaceKind kind);

// Which part of the scene a hit is on (finer than SurfaceKind: boxes may be background or
// occluders).
enum class SceneObject : uint8_t { kNone = 0, kTree, kGround, kHedge, kBox, kPost, kShrub, kRope };

// An axis-aligned (after `yaw_rad` about +Z) box standing in the scene: a crate, a bench, a bin.
struct SceneBox {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_extent = Eigen::Vector3d(0.2, 0.2, 0.2);
  double yaw_rad = 0.0;
  Eigen::Vector3f albedo = Eigen::Vector3f(0.5f, 0.5f, 0.5f);
  SurfaceKind kind = SurfaceKind::kBackground;  // or kOccluder
};

// A vertical post (a garden stake, a lamp post) standing on the ground.
struct ScenePost {
  Eigen::Vector2d base = Eigen::Vector2d::Zero();  // x, y on the ground
  double radius_m = 0.04;
  double height_m = 1.8;
};

// A leafless shrub: twigs radiating from a centre, of about `radius_m`.
struct SceneShrub {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius_m = 0.5;
  int twigs = 60;
  uint64_t seed = 1;
};

struct SceneOptions {
  bool ground = true;
  double ground_half_size_m = 60.0;
  // A ring of hedge around `hedge_center` (the tree's base by default): in the colour image, not
  // in the depth image when its radius is beyond the cameras' reach.
  bool hedge = true;
  Eigen::Vector2d hedge_center = Eigen::Vector2d::Zero();
  double hedge_radius_m = 8.0;
  double hedge_height_m = 2.5;
  std::vector<SceneBox> boxes;
  std::vector<ScenePost> posts;
  std::vector<SceneShrub> shrubs;
  // Red tape bands at the tree's markers.
  bool markers = true;
  double tape_width_m = 0.04;
  double rope_radius_m = 0.004;
  // Branches are traced as triangle tubes whose facets stay this close to the true generalized
  // cylinders (sensor_tree_tubes.h).
  double tube_tolerance_m = 0.00025;
  // Lighting: direction towards the sun (world), sun and ambient strength.
  Eigen::Vector3d sun_direction = Eigen::Vector3d(0.55, -0.60, 0.58);
  double sun_intensity = 0.75;
  double ambient_intensity = 0.45;
  uint64_t texture_seed = 1;
};

// A scene around `tree`: ground, hedge beyond the reach of cameras 1.5-3 m from the crown, three
// low objects near the trunk, a sun drawn from `seed`; with `hard`, also a post and a shrub near
// the tree (occluders).
SceneOptions DefaultSceneOptions(const Tree& tree, uint64_t seed, bool hard = false);

// Throws InputError naming `source` and the field for a value that is not finite, a size that
// is not positive, a zero sun direction.
void ValidateSceneOptions(const SceneOptions& options, const std::string& source);

// A rope tied to a branch at a rest arc length (it follows the branch's pose) and pulled towards
// a fixed anchor.
struct RopeSegment {
  int branch = 0;
  double arc_length = 0.0;
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
};

// A tape band: the surface of `branch` between rest arc lengths `begin` and `end`.
struct MarkerBand {
  int marker_index = 0;  // in tree.markers
  int id = 0;            // tree.markers[marker_index].id
  int branch = 0;
  double begin = 0.0;
  double end = 0.0;
};

struct SceneHit {
  SurfaceKind kind = SurfaceKind::kNone;
  double t = 0.0;  // along the ray: point = origin + t direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, facing the ray's origin
  // Branches, the rope, shrub twigs and posts are curves: their radius at the hit.
  double radius = 0.0;
  // Branches.
  int branch = -1;
  double arc_length = 0.0;  // rest arc length from the branch base
  double angle = 0.0;       // around the axis, from the rest frame's u towards w
  int marker = -1;          // marker id when inside a tape band
  int marker_index = -1;    // its index in tree.markers
  SceneObject object = SceneObject::kNone;
  int object_index = -1;  // boxes, posts, shrubs: the index in SceneOptions' list
  double along = 0.0;     // rope and twigs: distance from the curve's start; hedge: along the ring
  bool hit() const { return kind != SurfaceKind::kNone; }
};

class SensorScene {
 public:
  // Copies the tree; the pose starts at rest. Throws InputError for an invalid tree (core
  // Validate) or options.
  explicit SensorScene(const Tree& tree, const SceneOptions& options = {});
  ~SensorScene();
  SensorScene(SensorScene&&) noexcept;
  SensorScene& operator=(SensorScene&&) noexcept;
  SensorScene(const SensorScene&) = delete;
  SensorScene& operator=(const SensorScene&) = delete;

  // Moves the branches. Throws InputError (and keeps the old pose) when the pose does not match
  // the tree (branch or node counts) or holds a coordinate that is not finite.
  void SetPose(const TreePose& pose);
  // A rope, or none. Throws InputError for an unknown branch or a non-finite anchor or arc length.
  void SetRope(const std::optional<RopeSegment>& rope);

  const Tree& tree() const;
  const TreePose& pose() const;
  const SceneOptions& options() const;
  const std::optional<RopeSegment>& rope() const;
  // The tape bands, one per tree marker (empty when options.markers is off).
  const std::vector<MarkerBand>& marker_bands() const;

  // The nearest surface along origin + t direction for t in (t_near, t_far); `direction` need
  // not be unit.
  SceneHit Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                     double t_near = 0.0,
                     double t_far = std::numeric_limits<double>::infinity()) const;
  // Intersect() for many rays from one origin (a camera's pixels): coherent rays traced as
  // packets, several times faster than one by one. `hits` must have the size of `directions`.
  void IntersectCoherent(const Eigen::Vector3d& origin, std::span<const Eigen::Vector3d> directions,
                         std::span<SceneHit> hits) const;
  // Whether anything lies along the ray in (t_near, t_far) (shadow rays).
  bool Occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_near,
                double t_far) const;
  // Occluded() for many rays along one direction (shadow rays towards the sun), in packets.
  // `occluded` must have the size of `origins`.
  void OccludedCoherent(std::span<const Eigen::Vector3d> origins, const Eigen::Vector3d& direction,
                        double t_near, double t_far, std::span<uint8_t> occluded) const;
  // The nearest hit on the tape band `marker_index` as if nothing else were in the scene (only the
  // band's branch near the band is traced); kNone when the ray misses the band.
  SceneHit IntersectMarkerBand(int marker_index, const Eigen::Vector3d& origin,
                               const Eigen::Vector3d& direction) const;

  // Radius of `branch` at a rest arc length (linear between nodes).
  double RadiusAt(int branch, double arc_length) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simtree::synth
