#pragma once
// A rope pulling one point of one branch towards an anchor: the pull test of the paper (Section
// III-C: "a static load" by pulling, then release) and the viewer's mouse drag. The rope pulls with
// a given tension, or with the tension that displaces the point statically by a given distance
// towards the anchor (what a pull test that pulls "by 10 cm" does).

#include <string>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::dynamics {

struct Rope {
  enum class Mode { kForce, kDisplacement };

  int branch = 0;
  double arc_length = -1.0;  // metres from the branch base; negative = the tip
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // world; the rope pulls the point towards it
  Mode mode = Mode::kForce;
  double force_n = 0.0;         // kForce: tension (N)
  double displacement_m = 0.0;  // kDisplacement: static displacement towards the anchor (m)
};

// "force", "displacement".
const char* ToString(Rope::Mode mode);

// The rope's arc length on its branch (the tip for a negative value). Throws InputError naming
// `source` when the branch does not exist, the arc length is past the tip or a value is not finite
// or negative.
double ValidateRope(const Tree& tree, const Rope& rope, const std::string& source = "rope");

// Where a pull goes, as written on the command line: "BRANCH" (its tip) or "BRANCH@S" (S metres
// from its base). Throws InputError on anything else.
struct PullTarget {
  int branch = 0;
  double arc_length = -1.0;  // negative = the tip
};
PullTarget ParsePullTarget(const std::string& text, const std::string& where = "--pull");

// The default pull direction at a point of a branch: straight down where the branch is not
// vertical (made perpendicular to the branch there), otherwise horizontally away from the trunk
// axis; world X as the last resort. Unit length.
Eigen::Vector3d DefaultPullDirection(const Tree& tree, int branch, double arc_length);

}  // namespace simtree::dynamics
