#pragma once
// Live material edits of the viewer's panel: a branch's (or a whole level's) natural frequency,
// damping ratio or stiffness, as the authors' demo lets a user tune them. The three modes keep
// their ratios to the first (a measured tree's modes differ), and k = 4 m pi^2 f^2 holds after
// every edit: a new frequency keeps the mass (k follows), a new stiffness keeps the frequencies
// (the mass follows).

#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::viewer {

enum class MaterialProperty { kFrequency, kDamping, kStiffness };

// What an edit applies to: one branch, or every branch of its level.
enum class MaterialScope { kBranch, kLevel };
const char* ToString(MaterialScope scope);  // "branch", "level"

// The demo's slider ranges: 0.1-10 Hz, 0.005-1, 100-50000 N/m.
struct PropertyRange {
  double min = 0.0, max = 0.0;
};
PropertyRange RangeOf(MaterialProperty property);
const char* ToString(MaterialProperty property);
// "frequency", "damping" or "stiffness"; throws InputError naming `where` otherwise.
MaterialProperty ParseMaterialProperty(const std::string& name, const std::string& where);

// The first mode's frequency, the first mode's damping ratio, or k.
double PropertyValue(const Material& material, MaterialProperty property);
// `material` with the property set to `value` (see above). Throws InputError for a value that is
// not finite or not positive (damping may be 0).
Material WithProperty(const Material& material, MaterialProperty property, double value);

// Sets the property on the branches given, live; returns how many changed.
int EditMaterials(dynamics::TreeDynamics& sim, const std::vector<int>& branches,
                  MaterialProperty property, double value);
// The branches of one level.
std::vector<int> BranchesOfLevel(const Tree& tree, int level);

}  // namespace simtree::viewer
