#pragma once
// Typical material values of a kind of tree, for a tree that had no pull test: the middle of the
// ranges the paper measured on its trees (Table IV), one value for every branch. The paper's
// trees swing near one frequency across their branches (Table IV's ranges are narrow, and on
// synthetic pull tests the unmarked branches' frequencies fall into a few whole-tree modes:
// docs/simready.md, "Interpolation"), so no size law is assumed.

#include <string>
#include <vector>

namespace simtree::simready {

struct TypicalMaterial {
  std::string species;  // "magnolia"
  double min_frequency_hz = 0.0, max_frequency_hz = 0.0;
  double min_damping_ratio = 0.0, max_damping_ratio = 0.0;

  double frequency_hz() const { return 0.5 * (min_frequency_hz + max_frequency_hz); }
  double damping_ratio() const { return 0.5 * (min_damping_ratio + max_damping_ratio); }
};

// The paper's Table IV rows: acer_palmatum, magnolia, acer_rubrum (synth's species names).
const std::vector<TypicalMaterial>& TypicalMaterials();

// The row of `species` (case and '-'/' ' vs '_' ignored); throws InputError naming the option
// `--species` and listing the known species otherwise.
const TypicalMaterial& FindTypicalMaterial(const std::string& species);

}  // namespace simtree::simready
