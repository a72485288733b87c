#pragma once
// The tree as an articulated body for robot simulators: every branch a chain of rigid capsule
// segments, joined at each segment's base by two bending hinges (and optionally a twist hinge),
// the trunk's first segment hinged on the world. One format-neutral model that the MJCF, URDF and
// SDF writers print; robot_calibration.h gives its joints their stiffness and damping.
//
// Every body frame is parallel to the world frame (no rotations anywhere), so a body's position
// relative to its parent is a plain difference and a joint axis is the same vector in every frame.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::robots {

// When a segment gets a twist hinge about its own axis.
enum class TwistHinges {
  kNone,              // bending only
  kBranchesWithKids,  // branches that carry children: their twist swings the sub-trees
  kAll,
};
// "none", "auto", "all"; ParseTwistHinges throws InputError on anything else.
const char* ToString(TwistHinges twist);
TwistHinges ParseTwistHinges(const std::string& text, const std::string& where = "--twist");

struct RobotModelOptions {
  int segments_per_branch = 4;  // rigid segments per branch (>= 1)
  // Tree-wide budget of segment bodies: a tree whose branches would need more gets fewer
  // segments per branch (never fewer than 1); 0 = no budget.
  int max_bodies = 20000;
  double wood_density_kg_m3 = 900.0;  // segment masses: density times frustum volume
  TwistHinges twist = TwistHinges::kBranchesWithKids;
  // Whether a robot's geoms can touch the tree's capsules (MJCF contype 2: geoms with conaffinity
  // bit 2 meet them). Off, the capsules are left out of collision detection altogether, which
  // was 36-41% of a step at 1,000 branches (docs/benchmarks.md).
  bool collidable = false;

  void Validate() const;  // throws OptionError naming the field
};

// The three hinge kinds at a segment's base. bend_u deflects the branch along its u axis, so its
// hinge turns about w; bend_w's turns about u.
enum class HingeKind { kBendU = 0, kBendW = 1, kTwist = 2 };

struct Hinge {
  HingeKind kind = HingeKind::kBendU;
  std::string name;                                 // "b3_s1_bu"
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, world (= every frame)
  double stiffness = 0.0;                           // N m / rad
  double damping = 0.0;                             // N m s / rad
  double spring_reference = 0.0;  // rad: the angle the spring pulls to (gravity compensation)
};

// One rigid segment of a branch: a capsule from `base` to `tip` with explicit inertia.
struct Segment {
  std::string name;  // "b3_s1"
  int branch = 0;
  int index = 0;    // along the branch, 0 at its base
  int parent = -1;  // index into RobotModel::segments; -1 = the world
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  // world, at rest; the hinges sit here
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double radius = 0.0;                    // capsule radius (m)
  double arc_begin = 0.0, arc_end = 0.0;  // along the branch (m)
  double mass_kg = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  // world
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         // about the centre of mass, world axes
  std::vector<Hinge> hinges;
};

// A named point on a segment: a tape marker, a branch's grasp point or its tip.
struct Site {
  enum class Kind { kMarker, kGrasp, kTip };
  Kind kind = Kind::kMarker;
  std::string name;  // "marker_M3", "grasp_b3", "tip_b3"
  int segment = 0;
  int branch = 0;
  int marker_id = -1;                                  // kMarker
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, at rest
};

struct RobotModel {
  std::string name = "tree";
  std::vector<Segment> segments;  // parents before children
  std::vector<Site> sites;
  std::vector<std::vector<int>> branch_segments;  // segment indices of each branch, base to tip
  int segments_per_branch = 0;                    // after the budget
  double time_step_s = 0.0;  // a simulator step stable for the stiffest hinge (s)
  double total_mass_kg = 0.0;
  double gravity = 9.81;    // m/s^2 the spring references balance (0: none)
  bool collidable = false;  // RobotModelOptions::collidable

  int HingeCount() const;
  const Site* FindSite(const std::string& name) const;
};

// The chain geometry, masses and sites of `tree` (hinge stiffness and damping still zero: see
// CalibrateRobotModel). Throws InputError naming the branch for a branch without a material, a
// radius that is not positive or a branch of zero length.
RobotModel BuildRobotModel(const Tree& tree, const RobotModelOptions& options,
                           const std::string& source = "tree");

// The segment of `branch` that holds arc length s (the last one holds the tip).
int SegmentAt(const RobotModel& model, int branch, double arc_length);

}  // namespace simtree::robots
