#pragma once
// identify/placements.json (`simtree.marker_placements` v1): where each tracked marker sits on
// the reconstructed tree, its link, and which markers were held out of identification.
//
//   {"format": "simtree.marker_placements", "version": 1, "held_out": [4, 9],
//    "markers": [{"id": 0, "label": "M0", "parent": -1, "branch": 0, "arc_length": 0.8,
//                 "distance_m": 0.004, "rest_world": [x, y, z]}, ...]}
//
// Positions are in the registration frame (the tree's); markers without a branch are left out.

#include <filesystem>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/identification/marker_assignment.h"

namespace simtree::pipeline::detail {

struct PlacedMarker {
  MarkerLink link;
  identification::MarkerPlacement placement;
};

struct Placements {
  std::vector<PlacedMarker> markers;
  std::vector<int> held_out;

  bool IsHeldOut(int id) const;
};

void WritePlacements(const identification::TreeMarkers& placed, const std::vector<int>& held_out,
                     const std::filesystem::path& path);
// Throws InputError naming the file and field.
Placements ReadPlacements(const std::filesystem::path& path);

// `tree` with the placed markers (each at its arc length on its branch; a parent that is not
// placed becomes -1).
Tree WithMarkers(Tree tree, const Placements& placements);

}  // namespace simtree::pipeline::detail
