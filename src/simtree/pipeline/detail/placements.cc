#include "simtree/pipeline/detail/placements.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/json_util.h"

namespace simtree::pipeline::detail {

bool Placements::IsHeldOut(int id) const {
  return std::find(held_out.begin(), held_out.end(), id) != held_out.end();
}

void WritePlacements(const identification::TreeMarkers& placed, const std::vector<int>& held_out,
                     const std::filesystem::path& path) {
  nlohmann::ordered_json markers = nlohmann::ordered_json::array();
  for (const MarkerLink& link : placed.markers) {
    const auto it =
        std::find_if(placed.placements.begin(), placed.placements.end(),
                     [&](const identification::MarkerPlacement& p) { return p.marker == link.id; });
    if (it == placed.placements.end() || it->branch < 0) continue;
    const Eigen::Vector3d& r = it->rest_world;
    markers.push_back({{"id", link.id},
                       {"label", link.label},
                       {"parent", link.parent},
                       {"branch", it->branch},
                       {"arc_length", it->arc_length},
                       {"distance_m", it->distance_m},
                       {"rest_world", {r.x(), r.y(), r.z()}}});
  }
  nlohmann::ordered_json doc = {{"format", "simtree.marker_placements"},
                                {"version", 1},
                                {"held_out", held_out},
                                {"markers", markers}};
  WriteFileAtomically(path, doc.dump(1) + "\n");
}

Placements ReadPlacements(const std::filesystem::path& path) {
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, "simtree.marker_placements", 1);
  Placements out;
  for (const JsonNode& id : doc.Field("held_out").ExpectArray().Items()) {
    out.held_out.push_back(id.Integer());
  }
  for (const JsonNode& m : doc.Field("markers").ExpectArray().Items()) {
    PlacedMarker p;
    p.link.id = m.Integer("id");
    p.link.label = m.String("label");
    p.link.parent = m.Integer("parent");
    p.link.branch = m.Integer("branch");
    p.placement.marker = p.link.id;
    p.placement.branch = m.Integer("branch");
    p.placement.arc_length = m.Number("arc_length");
    p.placement.distance_m = m.Number("distance_m");
    p.placement.rest_world = m.Vector3("rest_world");
    out.markers.push_back(p);
  }
  return out;
}

Tree WithMarkers(Tree tree, const Placements& placements) {
  tree.markers.clear();
  for (const PlacedMarker& p : placements.markers) {
    const int b = p.placement.branch;
    if (b < 0 || b >= tree.size()) continue;
    Marker marker;
    marker.id = p.link.id;
    marker.label = p.link.label;
    marker.branch = b;
    marker.arc_length = std::clamp(p.placement.arc_length, 0.0, tree.branches[b].Length());
    marker.parent = p.link.parent;
    marker.position = tree.branches[b].PointAt(marker.arc_length);
    tree.markers.push_back(marker);
  }
  for (Marker& m : tree.markers) {
    const bool placed = std::any_of(tree.markers.begin(), tree.markers.end(),
                                    [&](const Marker& other) { return other.id == m.parent; });
    if (!placed) m.parent = -1;
  }
  return tree;
}

}  // namespace simtree::pipeline::detail
