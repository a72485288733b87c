#include "simtree/viewer/detail/material_edit.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::viewer {

PropertyRange RangeOf(MaterialProperty property) {
  switch (property) {
    case MaterialProperty::kFrequency:
      return {0.1, 10.0};
    case MaterialProperty::kDamping:
      return {0.005, 1.0};
    case MaterialProperty::kStiffness:
      return {100.0, 50000.0};
  }
  return {};
}

const char* ToString(MaterialProperty property) {
  switch (property) {
    case MaterialProperty::kFrequency:
      return "frequency";
    case MaterialProperty::kDamping:
      return "damping";
    case MaterialProperty::kStiffness:
      return "stiffness";
  }
  return "?";
}

const char* ToString(MaterialScope scope) {
  return scope == MaterialScope::kLevel ? "level" : "branch";
}

MaterialProperty ParseMaterialProperty(const std::string& name, const std::string& where) {
  if (name == "frequency") return MaterialProperty::kFrequency;
  if (name == "damping") return MaterialProperty::kDamping;
  if (name == "stiffness") return MaterialProperty::kStiffness;
  throw InputError("", where,
                   fmt::format("expected frequency, damping or stiffness, got \"{}\"", name));
}

double PropertyValue(const Material& material, MaterialProperty property) {
  switch (property) {
    case MaterialProperty::kFrequency:
      return material.modes[0].frequency_hz;
    case MaterialProperty::kDamping:
      return material.modes[0].damping_ratio;
    case MaterialProperty::kStiffness:
      return material.stiffness;
  }
  return 0.0;
}

Material WithProperty(const Material& material, MaterialProperty property, double value) {
  const bool damping = property == MaterialProperty::kDamping;
  if (!std::isfinite(value) || value < 0.0 || (!damping && value == 0.0)) {
    throw InputError(
        "material", ToString(property),
        fmt::format("expected a finite value {} 0, got {}", damping ? ">=" : ">", value));
  }
  Material out = material;
  const double first = PropertyValue(material, property);
  switch (property) {
    case MaterialProperty::kFrequency: {
      const double ratio = first > 0.0 ? value / first : 1.0;
      // Higher modes first: SetFrequency of the first mode also updates k.
      for (int i = 2; i >= 0; --i) {
        const double f = i == 0 ? value : out.modes[i].frequency_hz * ratio;
        out.SetFrequency(out.modes[i].kind, f > 0.0 ? f : value);
      }
      break;
    }
    case MaterialProperty::kDamping: {
      for (int i = 0; i < 3; ++i) {
        out.modes[i].damping_ratio =
            first > 0.0 ? out.modes[i].damping_ratio * value / first : value;
      }
      out.modes[0].damping_ratio = value;
      break;
    }
    case MaterialProperty::kStiffness:
      out.SetStiffness(value);
      break;
  }
  return out;
}

int EditMaterials(dynamics::TreeDynamics& sim, const std::vector<int>& branches,
                  MaterialProperty property, double value) {
  int changed = 0;
  for (const int b : branches) {
    if (b < 0 || b >= sim.branch_count()) {
      throw InputError(
          "material", "branch",
          fmt::format("expected a branch id in [0, {}], got {}", sim.branch_count() - 1, b));
    }
    sim.SetMaterial(b, WithProperty(sim.material(b), property, value));
    ++changed;
  }
  return changed;
}

std::vector<int> BranchesOfLevel(const Tree& tree, int level) {
  std::vector<int> out;
  for (const Branch& b : tree.branches) {
    if (b.level == level) out.push_back(b.id);
  }
  return out;
}

}  // namespace simtree::viewer
