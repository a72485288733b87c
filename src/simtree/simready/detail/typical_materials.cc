#include "simtree/simready/detail/typical_materials.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::simready {

namespace {

std::string NormalizedName(const std::string& name) {
  std::string out;
  for (char c : name) {
    out += (c == '-' || c == ' ') ? '_' : static_cast<char>(std::tolower(static_cast<int>(c)));
  }
  return out;
}

}  // namespace

const std::vector<TypicalMaterial>& TypicalMaterials() {
  // Paper Table IV: natural frequency (Hz) and damping ratio ranges of the tested trees.
  static const std::vector<TypicalMaterial> kRows = {
      {"acer_palmatum", 1.07, 1.50, 0.031, 0.060},
      {"magnolia", 0.72, 1.19, 0.023, 0.033},
      {"acer_rubrum", 0.93, 1.50, 0.022, 0.056},
  };
  return kRows;
}

const TypicalMaterial& FindTypicalMaterial(const std::string& species) {
  const std::string wanted = NormalizedName(species);
  const std::vector<TypicalMaterial>& rows = TypicalMaterials();
  const auto it = std::find_if(rows.begin(), rows.end(),
                               [&](const TypicalMaterial& row) { return row.species == wanted; });
  if (it != rows.end()) return *it;
  std::string known;
  for (const TypicalMaterial& row : rows) known += (known.empty() ? "" : ", ") + row.species;
  throw InputError("--species", "",
                   fmt::format("no typical materials for \"{}\": known species are {} (the "
                               "paper's Table IV); give --default-material F,ZETA for another "
                               "kind of tree",
                               species, known));
}

}  // namespace simtree::simready
