#pragma once
// Scenes for the virtual sensor's tests: one-branch trees at known places, a bare scene (nothing
// but what a test adds), and the authors' tree02 with hand-placed tape markers.

#include <cmath>
#include <vector>

#include "simtree/core/frames.h"
#include "simtree/core/tree.h"
#include "simtree/core/tree_file.h"
#include "simtree/synth/detail/sensor_scene.h"
#include "test_util.h"

namespace simtree::test {

// A straight branch from `base` along `direction`, `length` long, of constant `radius`, as the
// trunk of a one-branch tree (nodes every 10 cm).
inline Tree OneBranchTree(const Eigen::Vector3d& base, const Eigen::Vector3d& direction,
                          double length, double radius) {
  Tree tree;
  tree.metadata.species = "test";
  Branch b;
  const int segments = std::max(1, static_cast<int>(std::ceil(length / 0.1)));
  for (int i = 0; i <= segments; ++i) {
    b.nodes.push_back({base + direction.normalized() * length * i / segments, radius});
  }
  tree.branches.push_back(b);
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

// A vertical cylinder of `radius` from z = 0 to z = `height` at (x, y).
inline Tree VerticalCylinder(double x, double y, double height, double radius) {
  return OneBranchTree({x, y, 0.0}, Eigen::Vector3d::UnitZ(), height, radius);
}

// Nothing but what the test adds: no ground, no hedge, no objects.
inline synth::SceneOptions BareScene() {
  synth::SceneOptions o;
  o.ground = false;
  o.hedge = false;
  return o;
}

// tree02 of the authors' demo (legacy options: 0.25 m per unit, Y up), about 4 m tall.
inline Tree Tree02() { return ReadTreeFile(SharedData("authors-demo/tree_model/tree02.txt")); }

// tree02 with tape markers at mid-length of the first branches of levels 0-3 thick enough to tape
// (radius >= 8 mm), linked to the marker on the nearest ancestor branch.
inline Tree Tree02WithMarkers() {
  Tree tree = Tree02();
  std::vector<int> marker_of_branch(tree.size(), -1);
  std::vector<int> per_level(8, 0);
  for (const Branch& b : tree.branches) {
    if (b.level > 3 || per_level[b.level] >= (b.level == 0 ? 1 : 3)) continue;
    const double s = 0.5 * b.Length();
    // Radius at the middle node.
    if (b.nodes[b.nodes.size() / 2].radius < 0.008) continue;
    Marker m;
    m.id = static_cast<int>(tree.markers.size());
    m.label = "M";  // (not "M" + std::to_string: GCC 12 warns falsely on that)
    m.label += std::to_string(m.id);
    m.branch = b.id;
    m.arc_length = s;
    m.position = b.PointAt(s);
    for (int p = b.parent; p >= 0; p = tree.branches[p].parent) {
      if (marker_of_branch[p] >= 0) {
        m.parent = marker_of_branch[p];
        break;
      }
    }
    if (m.parent < 0 && !tree.markers.empty()) m.parent = 0;
    marker_of_branch[b.id] = m.id;
    ++per_level[b.level];
    tree.markers.push_back(m);
  }
  return tree;
}

}  // namespace simtree::test
