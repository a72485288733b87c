#pragma once
// Materials for a tree that has none (the authors' tree02 ships without a parameter file): the
// values the authors' tree_parameters.txt gives each level of tree01, so a bare geometry can be
// pulled and released in the viewer and the renderer. Marked `default`, never `measured`.

#include "simtree/core/tree.h"

namespace simtree::viewer {

// Frequency (Hz), damping ratio and stiffness (N/m) of a level in the authors' tree01 file:
// trunk 3 / 0.02 / 30000, then 1.6 / 0.02 / 5000, 1.2 / 0.01 / 3000, 1.0 / 0.03 / 1000 and
// 1.2 / 0.04 / 1000 for level 4 and deeper.
Material DemoLevelMaterial(int level);

// Gives every branch without a material its level's DemoLevelMaterial; returns how many it set.
int FillMissingMaterials(Tree& tree);

}  // namespace simtree::viewer
