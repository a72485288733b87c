#include "simtree/identification/marker_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace simtree::identification {

std::vector<Eigen::Vector3d> RestPositions(const Trajectories& t, double rest_fraction) {
  std::vector<Eigen::Vector3d> out;
  for (const MarkerTrack& track : t.tracks) {
    std::vector<int> valid;
    for (int i = 0; i < t.frame_count(); ++i) {
      if (track.valid[i]) valid.push_back(i);
    }
    const size_t keep =
        std::max<size_t>(1, static_cast<size_t>(std::lround(valid.size() * rest_fraction)));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t k = valid.size() - std::min(keep, valid.size()); k < valid.size(); ++k) {
      sum += track.positions[valid[k]];
    }
    out.push_back(valid.empty() ? Eigen::Vector3d::Constant(std::nan(""))
                                : Eigen::Vector3d(sum / std::min(keep, valid.size())));
  }
  return out;
}

std::vector<MarkerPlacement> PlaceMarkersOnTree(const Tree& tree, const Trajectories& t,
                                                const Eigen::Isometry3d& world_from_camera) {
  const std::vector<Eigen::Vector3d> rest = RestPositions(t);
  std::vector<MarkerPlacement> out;
  for (int m = 0; m < t.marker_count(); ++m) {
    MarkerPlacement p;
    p.marker = t.tracks[m].marker;
    if (!rest[m].allFinite()) {
      out.push_back(p);
      continue;
    }
    p.rest_world = world_from_camera * rest[m];
    double best = std::numeric_limits<double>::infinity();
    for (const Branch& b : tree.branches) {
      const std::vector<double> s = b.ArcLengths();
      for (size_t i = 0; i + 1 < b.nodes.size(); ++i) {
        const Eigen::Vector3d a = b.nodes[i].position, c = b.nodes[i + 1].position;
        const Eigen::Vector3d ac = c - a;
        const double len2 = ac.squaredNorm();
        const double u = len2 > 0 ? std::clamp((p.rest_world - a).dot(ac) / len2, 0.0, 1.0) : 0.0;
        const double radius = (1 - u) * b.nodes[i].radius + u * b.nodes[i + 1].radius;
        // Distance to the surface: a marker is taped on the bark, so thin and thick branches are
        // compared by how far outside each it lies.
        const double d = std::max(0.0, (p.rest_world - (a + u * ac)).norm() - radius);
        if (d < best) {
          best = d;
          p.branch = b.id;
          p.arc_length = s[i] + u * (s[i + 1] - s[i]);
          p.distance_m = d;
        }
      }
    }
    out.push_back(p);
  }
  return out;
}

std::vector<MarkerLink> LinkMarkersByTree(const Tree& tree,
                                          const std::vector<MarkerPlacement>& placements) {
  // Markers by branch, base to tip.
  std::vector<std::vector<const MarkerPlacement*>> on_branch(tree.size());
  for (const MarkerPlacement& p : placements) {
    if (p.branch >= 0) on_branch[p.branch].push_back(&p);
  }
  for (auto& list : on_branch) {
    std::sort(list.begin(), list.end(), [](const MarkerPlacement* a, const MarkerPlacement* b) {
      return a->arc_length < b->arc_length;
    });
  }
  std::vector<MarkerLink> out;
  std::vector<int> roots;
  for (const Branch& b : tree.branches) {
    for (size_t k = 0; k < on_branch[b.id].size(); ++k) {
      const MarkerPlacement& p = *on_branch[b.id][k];
      MarkerLink link{p.marker, fmt::format("M{}", p.marker), -1, p.branch};
      if (k > 0) {
        link.parent = on_branch[b.id][k - 1]->marker;
      } else {
        // Down the hierarchy: on each ancestor, the last marker below the attachment point (or,
        // failing that, any marker on it, the nearest to the attachment).
        double attach = b.is_trunk() ? 0.0 : tree.branches[b.parent].ArcLengths()[b.parent_node];
        for (int a = b.parent; a >= 0 && link.parent < 0; a = tree.branches[a].parent) {
          const auto& list = on_branch[a];
          const MarkerPlacement* below = nullptr;
          const MarkerPlacement* nearest = nullptr;
          for (const MarkerPlacement* q : list) {
            if (q->arc_length <= attach) below = q;
            if (!nearest ||
                std::abs(q->arc_length - attach) < std::abs(nearest->arc_length - attach)) {
              nearest = q;
            }
          }
          if (below || nearest) link.parent = (below ? below : nearest)->marker;
          const Branch& ancestor = tree.branches[a];
          attach = ancestor.is_trunk()
                       ? 0.0
                       : tree.branches[ancestor.parent].ArcLengths()[ancestor.parent_node];
        }
      }
      if (link.parent < 0) roots.push_back(static_cast<int>(out.size()));
      out.push_back(link);
    }
  }
  // One root: the first found (branches come parents first, so it is the lowest in the tree).
  for (size_t i = 1; i < roots.size(); ++i) out[roots[i]].parent = out[roots[0]].id;
  return out;
}

TreeMarkers MarkersOnTree(const Tree& tree, const Trajectories& trajectories,
                          const Eigen::Isometry3d& world_from_camera,
                          std::vector<MarkerLink> listed, double max_distance_m) {
  TreeMarkers out;
  out.placements = PlaceMarkersOnTree(tree, trajectories, world_from_camera);
  if (listed.empty()) {
    out.markers = LinkMarkersByTree(tree, out.placements);
    spdlog::info("linked {} markers along the static tree", out.markers.size());
  } else {
    for (MarkerLink& m : listed) {
      for (const MarkerPlacement& p : out.placements) {
        if (p.marker == m.id && !m.branch && p.branch >= 0) m.branch = p.branch;
      }
    }
    out.markers = std::move(listed);
  }
  for (const MarkerPlacement& p : out.placements) {
    if (p.branch >= 0 && p.distance_m > max_distance_m) {
      spdlog::warn("marker {} is {:.0f} mm from its nearest branch {}: is the camera pose right?",
                   p.marker, 1e3 * p.distance_m, p.branch);
    }
  }
  return out;
}

}  // namespace simtree::identification
