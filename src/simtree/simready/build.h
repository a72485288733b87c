#pragma once
// The simulation-ready tree (paper III-D): a static tree plus identified materials in, every
// branch with three modes, a modal mass, a stiffness and its frame out.
//
//  - Measured branches take their modes from materials.json; the others are interpolated
//    (interpolation.h) and marked so; nothing is measured at all -> an error, not a default.
//  - A measured value its own standard deviation or its distance from the others says not to
//    trust (uncertain_values.h) is flagged (Material::uncertain, the reason) and replaced by the
//    interpolation when that is more certain (`source` then `interpolated`).
//  - A tree without a pull test (BuildAssumedSimulationReadyTree): every branch gets one assumed
//    frequency and damping ratio (typical of its kind of tree: typical_materials.h, or the
//    user's), marked `assumed`, so that a static scan alone still animates.
//  - Mass: core's Material::mass_kg is the modal mass m of paper Eq. 6 for modes normalised to a
//    unit tip deflection (a static tip force F bends the branch by F / k, k = 4 m pi^2 f^2). For a
//    cantilever whose first mode shape is phi (phi(tip) = 1) the modal mass is
//        m = integral_0^L mu(s) phi(s/L)^2 ds  +  sum over children c of M_c phi(s_c/L)^2,
//    with mu = rho pi r(s)^2 the wood's mass per length along the branch and M_c the whole mass of
//    the sub-tree that rides on the branch at arc length s_c (it moves with the branch there).
//    For a uniform branch with no children this is a quarter of its mass. phi is the first
//    Euler-Bernoulli cantilever mode of a uniform beam.
//  - Stiffness k = 4 m pi^2 f^2 of the first mode (bend_u).
//  - Frames (u, v, w) from the branch and its parent (paper Fig. 9b; core/frames.h), levels from
//    the hierarchy, and optionally ids renumbered in depth-first order (paper: "a standard
//    depth-first-search algorithm is employed to create the hierarchy").
//
// Usage:
//   const simtree::Tree static_tree = simtree::ReadTreeJson("static.json");
//   const auto materials = simtree::identification::ReadMaterialsJson("materials.json");
//   simtree::simready::BuildReport report;
//   const simtree::Tree tree =
//       simtree::simready::BuildSimulationReadyTree(static_tree, materials, {}, &report);
//   // No pull test: typical values of the kind of tree, marked assumed.
//   const simtree::Tree assumed = simtree::simready::BuildAssumedSimulationReadyTree(
//       static_tree, simtree::simready::AssumedMaterialOf("magnolia"));

#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/identification/materials_file.h"
#include "simtree/simready/detail/interpolation.h"
#include "simtree/simready/detail/typical_materials.h"
#include "simtree/simready/detail/uncertain_values.h"

namespace simtree::simready {

struct BuildOptions {
  double wood_density_kg_m3 = 900.0;  // green wood, bark and water included, kg/m^3
  // Count the sub-trees riding on a branch in its modal mass (see above).
  bool include_subtree_mass = true;
  // Renumber branches in depth-first pre-order (each sub-tree then has consecutive ids); markers
  // follow their branches.
  bool renumber_depth_first = false;
  InterpolationOptions interpolation;  // for the branches no marker measured
  UncertaintyOptions uncertainty;      // measured values flagged, and replaced, as uncertain

  // Throws InputError naming the field ("interpolation.min_branches_cantilever") for a value out
  // of range.
  void Validate() const;
};

// One frequency and damping ratio given to every branch of a tree without a pull test.
struct AssumedMaterial {
  double frequency_hz = 0.0;   // every mode's natural frequency, Hz
  double damping_ratio = 0.0;  // every mode's damping ratio, in (0, 1)
  std::string origin;          // where the values come from, for the log: "magnolia, Table IV"

  // Throws InputError naming the field for a frequency outside 0.01-100 Hz or a damping ratio
  // outside (0, 1).
  void Validate() const;
};

// The middle of the paper's Table IV ranges for `species` (typical_materials.h); throws
// InputError listing the known species otherwise.
AssumedMaterial AssumedMaterialOf(const std::string& species);

struct BuildReport {
  int measured = 0;      // branches whose modes come from materials.json
  int interpolated = 0;  // branches whose modes the interpolation gave
  int assumed = 0;       // branches given an AssumedMaterial (a tree without a pull test)
  int flagged = 0;       // measured values flagged uncertain (kept or replaced)
  int replaced = 0;      // of those, replaced by the interpolation (counted in `interpolated`)
  // One line per flagged value: "branch 7: frequency sd 31.2% of its value (over 10%); replaced".
  std::vector<std::string> flagged_why;
  InterpolationModel interpolation;
  double total_mass_kg = 0.0;  // the whole tree, density times volume
};

// The first bending mode shape of a uniform Euler-Bernoulli cantilever at xi = s / L in [0, 1],
// normalised so phi(1) = 1.
double CantileverModeShape(double xi);

// Modal mass of `branch` (see above), with `subtree_mass[c]` the whole mass of the sub-tree of
// branch c (empty: no children counted).
double BranchModalMass(const Tree& tree, int branch, double density_kg_m3,
                       const std::vector<double>& subtree_mass = {});

// Mass of every branch's sub-tree (the branch and all below it), density times volume.
std::vector<double> SubtreeMasses(const Tree& tree, double density_kg_m3);

// Throws InputError for options out of range, and when materials name branches the tree lacks or
// measure none of its branches.
Tree BuildSimulationReadyTree(const Tree& static_tree,
                              const identification::MaterialsFile& materials,
                              const BuildOptions& options = {}, BuildReport* report = nullptr);

// A tree without a pull test: every branch `assumed`'s frequency and damping on all three modes,
// marked MaterialSource::kAssumed, with modal masses and stiffnesses as above. Throws InputError
// for options or values out of range.
Tree BuildAssumedSimulationReadyTree(const Tree& static_tree, const AssumedMaterial& assumed,
                                     const BuildOptions& options = {},
                                     BuildReport* report = nullptr);

// Branch ids in depth-first order become 0..n-1; parents, markers follow. Returns the new tree
// and, in `new_id`, the new id of each old one.
Tree RenumberDepthFirst(const Tree& tree, std::vector<int>* new_id = nullptr);

}  // namespace simtree::simready
