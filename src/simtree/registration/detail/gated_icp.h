#pragma once
// Fine registration (paper III-A): point-to-plane ICP whose correspondences are rejected by
// distance and by the angle between their normals, coarse to fine.
//
// The normal-angle gate matters on trees: seen from opposite sides, the front of a thin branch in
// one view lies a branch diameter from its back in the other, and plain point-to-plane ICP pulls
// them together (NOTES.md: ~47 mm of drift at 180 degrees even when started at the true pose).
// Normals are oriented towards each view's camera, so a front and a back disagree by more than
// the gate and never pair. Open3D's ICP has no such gate, hence this implementation.
// Pairwise registration (pairwise.h) runs it without the gate by default: the gate keeps mostly
// grazing correspondences, whose pull is the most biased, and AlignMedialAxes below undoes the
// shells' pull instead (docs/registration.md).

#include <optional>
#include <vector>

#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <Eigen/Geometry>

namespace simtree::registration {

// What a correspondence's residual is measured along.
enum class IcpObjective {
  kPointToPlane,  // the target point's normal
  // The sum of both points' normals (Rusinkiewicz 2019, "A symmetric objective function for
  // ICP"): two points on one circle (a branch's cross-section) have a zero residual wherever on
  // it each lies, so the two one-sided shells of a branch seen from opposite sides are not pulled
  // together; pairs whose normals disagree weigh less (opposite normals: nothing).
  kSymmetric,
};

struct GatedIcpOptions {
  IcpObjective objective = IcpObjective::kPointToPlane;  // what a residual is measured along
  // m, each > 0, largest first: one stage per distance, each up to `iterations_per_stage`.
  std::vector<double> max_distances_m = {0.06, 0.03, 0.015};
  int iterations_per_stage = 12;       // >= 1
  double max_normal_angle_deg = 45.0;  // deg, [0, 180]: the normal gate (180: none)
  // >= 0: residuals beyond this share of the stage distance are down-weighted (Huber; 0: none).
  double huber_share = 1.0 / 3.0;
  // [0, 1]: points whose neighbourhood is less plane-like than this (twigs, noise) take no part.
  double min_planarity = 0.0;
  double min_rotation_step = 2e-5;     // rad, >= 0: a stage stops at a smaller update
  double min_translation_step = 2e-5;  // m, >= 0: a stage stops at a smaller update
  size_t max_source_points = 6000;  // source points used (a seeded, spatially even sample; 0: all)
  uint64_t seed = 1;                // of the sample

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

struct IcpResult {
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  // Share of the (sampled) source points with a gated correspondence within the last stage's
  // distance, and the RMS point-to-point distance of those correspondences.
  double fitness = 0.0;
  double rmse_m = 0.0;
  int correspondences = 0;
  int iterations = 0;
  double seconds = 0.0;
};

// Both clouds need normals (camera-oriented). `target_tree` indexes `target`.
// A line both clouds see, such as a trunk's axis: the source segment must lie on the target's
// line. It pins the shift across the line and the tilt of the line, which two views far apart
// barely constrain through their few shared surfaces.
struct LineConstraint {
  Eigen::Vector3d source_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d source_direction = Eigen::Vector3d::UnitZ();
  double source_half_length_m = 0.0;
  Eigen::Vector3d target_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_direction = Eigen::Vector3d::UnitZ();
  // The line's weight as a share of all surface correspondences' weight.
  double weight = 1.0;
};

// A plane both clouds see, such as the ground: source points on it must stay on the target's.
// It pins the shift along the plane's normal and the tilt of the plane.
struct PlaneConstraint {
  std::vector<Eigen::Vector3d> source_points;  // on the source's plane, spread over it
  Eigen::Vector3d target_normal = Eigen::Vector3d::UnitZ();
  double target_offset = 0.0;  // target_normal . x + target_offset = 0 on the plane
  double weight = 1.0;         // as a share of all surface correspondences' weight
};

// What both views know besides their surfaces (each optional).
struct IcpPriors {
  std::optional<LineConstraint> line;
  std::optional<PlaneConstraint> plane;
};

// `source_planarity` and `target_planarity` (optional, one per point): points below
// `min_planarity` take no part (their normals are not trusted).
IcpResult GatedPointToPlaneIcp(
    const open3d::geometry::PointCloud& source, const open3d::geometry::PointCloud& target,
    const open3d::geometry::KDTreeFlann& target_tree, const Eigen::Isometry3d& initial,
    const GatedIcpOptions& options = {}, const std::vector<float>* source_planarity = nullptr,
    const std::vector<float>* target_planarity = nullptr, const IcpPriors& priors = {});

// The last step of fine registration: the shift (rotation kept), or with `rotation` the rigid
// move, that brings the source's medial points (registration_view.h) onto the target's. Surface
// ICP cannot find it when the views are far apart: each sees its own half of every branch, the
// halves barely overlap (grazing surfaces drop out), and ICP pulls the two shells together,
// moving the source towards the target camera by about half a branch radius, the thick lower
// branches more than the twigs (a lean). The branch axes both views agree on.
struct MedialShiftOptions {
  // m, each > 0, largest first: one stage per distance, each up to `iterations_per_stage`.
  std::vector<double> max_distances_m = {0.04, 0.02};
  int iterations_per_stage = 10;  // >= 1
  double min_step_m = 1e-4;       // m (and rad), >= 0: a stage stops at a smaller step
  int min_matches = 30;           // >= 3: with fewer matched source points the start is kept
  // Fit the rotation too (a rigid, point-to-point fit of the medial points; Huber-weighted).
  bool rotation = false;

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};
struct MedialShiftResult {
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  // Applied after the start, target frame (with `rotation`: how far the matched points' centre
  // moved).
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
  int matches = 0;
};
MedialShiftResult AlignMedialAxes(const open3d::geometry::PointCloud& source_medial,
                                  const open3d::geometry::PointCloud& target_medial,
                                  const open3d::geometry::KDTreeFlann& target_tree,
                                  const Eigen::Isometry3d& initial,
                                  const MedialShiftOptions& options = {});

// Share of `source` points (after `transform`) with a target point within `distance_m` whose
// normal agrees within `max_normal_angle_deg` (180: no gate), and their RMS distance.
struct Overlap {
  double share = 0.0;
  double rmse_m = 0.0;
  int matched = 0;
};
Overlap MeasureOverlap(const open3d::geometry::PointCloud& source,
                       const open3d::geometry::PointCloud& target,
                       const open3d::geometry::KDTreeFlann& target_tree,
                       const Eigen::Isometry3d& transform, double distance_m,
                       double max_normal_angle_deg = 180.0);

}  // namespace simtree::registration
