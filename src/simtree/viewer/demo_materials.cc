#include "simtree/viewer/demo_materials.h"

#include <algorithm>
#include <array>

namespace simtree::viewer {

Material DemoLevelMaterial(int level) {
  struct Row {
    double frequency_hz, damping_ratio, stiffness;
  };
  // Read off shared/data/authors-demo/tree_parameters.txt against tree01's level colours.
  static constexpr std::array<Row, 5> kLevels = {Row{3.0, 0.02, 30000}, Row{1.6, 0.02, 5000},
                                                 Row{1.2, 0.01, 3000}, Row{1.0, 0.03, 1000},
                                                 Row{1.2, 0.04, 1000}};
  const Row& row = kLevels[std::clamp(level, 0, static_cast<int>(kLevels.size()) - 1)];
  return Material::FromFrequencyDampingStiffness(row.frequency_hz, row.damping_ratio, row.stiffness,
                                                 MaterialSource::kDefault);
}

int FillMissingMaterials(Tree& tree) {
  int filled = 0;
  for (Branch& b : tree.branches) {
    if (b.material) continue;
    b.material = DemoLevelMaterial(b.level);
    ++filled;
  }
  return filled;
}

}  // namespace simtree::viewer
