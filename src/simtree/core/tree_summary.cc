#include "simtree/core/tree_summary.h"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

namespace simtree {

TreeSummary Summarize(const Tree& tree) {
  TreeSummary s;
  s.branches = tree.size();
  s.nodes = tree.NodeCount();
  s.markers = static_cast<int>(tree.markers.size());
  if (tree.empty()) return s;
  s.branches_per_level.assign(tree.MaxLevel() + 1, 0);
  double fmin = std::numeric_limits<double>::infinity(), fmax = -fmin;
  double zmin = fmin, zmax = -fmin;
  for (const Branch& b : tree.branches) {
    ++s.branches_per_level[b.level];
    s.total_length_m += b.Length();
    if (!b.material) continue;
    ++s.with_material;
    s.uncertain += !b.material->uncertain.empty();
    switch (b.material->source) {
      case MaterialSource::kMeasured:
        ++s.measured;
        break;
      case MaterialSource::kInterpolated:
        ++s.interpolated;
        break;
      case MaterialSource::kDefault:
        ++s.defaulted;
        break;
      case MaterialSource::kAssumed:
        ++s.assumed;
        break;
    }
    for (const Mode& m : b.material->modes) {
      fmin = std::min(fmin, m.frequency_hz);
      fmax = std::max(fmax, m.frequency_hz);
      zmin = std::min(zmin, m.damping_ratio);
      zmax = std::max(zmax, m.damping_ratio);
    }
  }
  if (s.with_material > 0) {
    s.min_frequency_hz = fmin;
    s.max_frequency_hz = fmax;
    s.min_damping = zmin;
    s.max_damping = zmax;
  }
  tree.Bounds(&s.min_corner, &s.max_corner);
  s.height_m = s.max_corner.z() - tree.trunk().base().position.z();
  s.trunk_base_radius_m = tree.trunk().base().radius;
  return s;
}

std::string FormatMaterialSources(const TreeSummary& s) {
  std::string out = fmt::format("{} measured, {} interpolated, {} default", s.measured,
                                s.interpolated, s.defaulted);
  if (s.assumed > 0) out += fmt::format(", {} assumed", s.assumed);
  if (s.uncertain > 0) out += fmt::format("; {} flagged uncertain", s.uncertain);
  return out;
}

std::string FormatSummary(const TreeSummary& s) {
  std::string levels;
  for (size_t l = 0; l < s.branches_per_level.size(); ++l) {
    levels += fmt::format("{}{}: {}", l ? ", " : "", l, s.branches_per_level[l]);
  }
  const Eigen::Vector3d size = s.max_corner - s.min_corner;
  std::string out = fmt::format(
      "branches        {} (by level {})\n"
      "nodes           {}\n"
      "height          {:.2f} m (bounds {:.2f} x {:.2f} x {:.2f} m)\n"
      "trunk radius    {:.1f} cm at the base\n"
      "branch length   {:.2f} m in total",
      s.branches, levels, s.nodes, s.height_m, size.x(), size.y(), size.z(),
      100.0 * s.trunk_base_radius_m, s.total_length_m);
  if (s.with_material > 0) {
    out += fmt::format(
        "\nmaterials       {} of {} branches ({})\n"
        "frequency       {:.3g} - {:.3g} Hz\n"
        "damping ratio   {:.3g} - {:.3g}",
        s.with_material, s.branches, FormatMaterialSources(s), s.min_frequency_hz,
        s.max_frequency_hz, s.min_damping, s.max_damping);
    if (s.assumed > 0) {
      out +=
          "\n                assumed values are typical of the kind of tree, not measured: "
          "a pull test (`simtree identify`) measures them";
    }
  } else {
    out += "\nmaterials       none (a static tree; `simtree build` adds them)";
  }
  if (s.markers > 0) out += fmt::format("\nmarkers         {}", s.markers);
  return out;
}

}  // namespace simtree
