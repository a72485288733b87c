#include "simtree/synth/species.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace simtree::synth {
namespace {

constexpr const char* kSpeciesFormat = "simtree.species";
constexpr int kSpeciesFormatVersion = 2;  // 2: longest_path_ratio
constexpr int kMinLevels = 4;
constexpr int kMaxLevels = 6;

// ---------------------------------------------------------------------------------------------
// One description of every field (name, range) walked by three visitors: the JSON writer, the
// strict JSON reader and the range check. `P` is SpeciesParams or const SpeciesParams.

template <typename Shape, typename V>
void VisitAxisShape(Shape& s, V& v) {
  v.Number("node_spacing_m", s.node_spacing_m, 0.01, 0.2);
  v.Number("bend_wavelength_m", s.bend_wavelength_m, 0.05, 10.0);
  v.Number("bend_angle_deg", s.bend_angle_deg, 0.0, 90.0);
  v.Number("tropism_base_per_m", s.tropism_base_per_m, -10.0, 10.0);
  v.Number("tropism_tip_per_m", s.tropism_tip_per_m, -10.0, 10.0);
}

template <typename Buds, typename V>
void VisitBuds(Buds& b, V& v) {
  v.Number("spacing_m", b.spacing_m, 0.01, 2.0);
  v.Number("break_probability", b.break_probability, 0.0, 1.0);
  v.Number("lateral_preference", b.lateral_preference, 0.0, 1.0);
}

template <typename Trunk, typename V>
void VisitTrunk(Trunk& t, V& v) {
  v.Number("length_fraction", t.length_fraction, 0.1, 1.0);
  v.Number("lean_deg", t.lean_deg, 0.0, 30.0);
  v.Number("clear_bole_fraction", t.clear_bole_fraction, 0.0, 0.95);
  v.Integer("fork_count", t.fork_count, 0, 8);
  v.Number("fork_angle_deg", t.fork_angle_deg, 0.0, 90.0);
  v.Number("fork_angle_spread_deg", t.fork_angle_spread_deg, 0.0, 45.0);
  v.Number("fork_length_ratio", t.fork_length_ratio, 0.1, 3.0);
  v.Group("shape", [&] { VisitAxisShape(t.shape, v); });
  v.Group("buds", [&] { VisitBuds(t.buds, v); });
}

template <typename Level, typename V>
void VisitLevel(Level& l, V& v) {
  v.Number("branching_angle_deg", l.branching_angle_deg, 0.0, 150.0);
  v.Number("branching_angle_spread_deg", l.branching_angle_spread_deg, 0.0, 60.0);
  v.Number("length_ratio", l.length_ratio, 0.01, 2.0);
  v.Number("length_spread", l.length_spread, 0.0, 0.9);
  v.Number("remaining_length_weight", l.remaining_length_weight, 0.0, 1.0);
  v.Number("branching_start_fraction", l.branching_start_fraction, 0.0, 0.95);
  v.Group("shape", [&] { VisitAxisShape(l.shape, v); });
  v.Group("buds", [&] { VisitBuds(l.buds, v); });
}

template <typename Wood, typename V>
void VisitWood(Wood& w, V& v) {
  v.Number("youngs_modulus_pa", w.youngs_modulus_pa, 1e8, 1e11);
  v.Number("shear_modulus_pa", w.shear_modulus_pa, 1e7, 5e10);
  v.Number("density_kg_m3", w.density_kg_m3, 100.0, 2000.0);
  v.Number("mature_radius_m", w.mature_radius_m, 0.001, 1.0);
  v.Number("young_wood_exponent", w.young_wood_exponent, 0.0, 3.0);
  v.List("damping", w.damping, 2, 2, [&](auto& anchor) {
    v.Number("frequency_hz", anchor.frequency_hz, 0.01, 200.0);
    v.Number("damping_ratio", anchor.damping_ratio, 0.0, 1.0);
  });
}

template <typename P, typename V>
void VisitSpecies(P& p, V& v) {
  v.Text("name", p.name);
  v.Text("description", p.description);
  v.Number("height_m", p.height_m, 1.0, 8.0);
  v.Number("height_spread", p.height_spread, 0.0, 0.5);
  v.Number("trunk_base_radius_m", p.trunk_base_radius_m, 0.005, 0.3);
  v.Number("trunk_radius_spread", p.trunk_radius_spread, 0.0, 0.5);
  v.Number("longest_path_ratio", p.longest_path_ratio, 0.5, 3.0);
  v.Number("min_twig_radius_m", p.min_twig_radius_m, 0.0005, 0.01);
  v.Number("pipe_exponent", p.pipe_exponent, 1.5, 3.5);
  v.Number("shed_shoots_per_m", p.shed_shoots_per_m, 0.0, 100.0);
  v.Phyllotaxis("phyllotaxis", p.phyllotaxis);
  v.Number("divergence_angle_deg", p.divergence_angle_deg, 0.0, 360.0);
  v.Number("phyllotaxis_jitter_deg", p.phyllotaxis_jitter_deg, 0.0, 45.0);
  v.Number("crown_peak_position", p.crown_peak_position, 0.0, 1.0);
  v.Number("crown_sharpness", p.crown_sharpness, 0.0, 20.0);
  v.Number("crown_floor", p.crown_floor, 0.0, 1.0);
  v.Number("min_branch_length_m", p.min_branch_length_m, 0.02, 1.0);
  v.Group("trunk", [&] { VisitTrunk(p.trunk, v); });
  v.List("levels", p.levels, kMinLevels, kMaxLevels, [&](auto& level) { VisitLevel(level, v); });
  v.Group("wood", [&] { VisitWood(p.wood, v); });
  v.Number("root_plate_stiffness_ratio", p.root_plate_stiffness_ratio, 0.0, 1e4);
}

// The path of the field being visited ("levels[2].shape.node_spacing_m").
class PathTracker {
 public:
  std::string At(const std::string& key) const { return Member(prefix_, key); }
  template <typename F>
  void Nest(const std::string& prefix, F&& f) {
    const std::string saved = prefix_;
    prefix_ = prefix;
    f();
    prefix_ = saved;
  }
  const std::string& prefix() const { return prefix_; }

 private:
  std::string prefix_;
};

// Range check of a struct in memory.
class RangeCheck {
 public:
  explicit RangeCheck(std::string source) : source_(std::move(source)) {}

  void Number(const char* key, double value, double lo, double hi) {
    if (!(std::isfinite(value) && value >= lo && value <= hi)) {
      throw InputError(source_, path_.At(key),
                       fmt::format("expected a number in [{}, {}], got {}", lo, hi, value));
    }
  }
  void Integer(const char* key, int value, int lo, int hi) {
    if (value < lo || value > hi) {
      throw InputError(source_, path_.At(key),
                       fmt::format("expected an integer in [{}, {}], got {}", lo, hi, value));
    }
  }
  void Text(const char*, const std::string&) {}
  void Phyllotaxis(const char*, synth::Phyllotaxis) {}
  template <typename F>
  void Group(const char* key, F&& f) {
    path_.Nest(path_.At(key), f);
  }
  template <typename Container, typename F>
  void List(const char* key, const Container& items, int lo, int hi, F&& f) {
    const auto count = static_cast<int>(items.size());
    if (count < lo || count > hi) {
      throw InputError(source_, path_.At(key),
                       lo == hi ? fmt::format("expected {} entries, got {}", lo, count)
                                : fmt::format("expected {} to {} entries, got {}", lo, hi, count));
    }
    const std::string at = path_.At(key);
    for (size_t i = 0; i < items.size(); ++i) {
      path_.Nest(Element(at, i), [&] { f(items[i]); });
    }
  }

 private:
  std::string source_;
  PathTracker path_;
};

// Writes every field into an ordered JSON object.
class JsonWriter {
 public:
  explicit JsonWriter(nlohmann::ordered_json* out) : out_(out) {}

  void Number(const char* key, double value, double, double) { (*out_)[key] = value; }
  void Integer(const char* key, int value, int, int) { (*out_)[key] = value; }
  void Text(const char* key, const std::string& value) { (*out_)[key] = value; }
  void Phyllotaxis(const char* key, synth::Phyllotaxis value) { (*out_)[key] = ToString(value); }
  template <typename F>
  void Group(const char* key, F&& f) {
    nlohmann::ordered_json* saved = out_;
    nlohmann::ordered_json group = nlohmann::ordered_json::object();
    out_ = &group;
    f();
    out_ = saved;
    (*out_)[key] = std::move(group);
  }
  template <typename Container, typename F>
  void List(const char* key, const Container& items, int, int, F&& f) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    nlohmann::ordered_json* saved = out_;
    for (const auto& item : items) {
      nlohmann::ordered_json element = nlohmann::ordered_json::object();
      out_ = &element;
      f(item);
      list.push_back(std::move(element));
    }
    out_ = saved;
    (*out_)[key] = std::move(list);
  }

 private:
  nlohmann::ordered_json* out_;
};

// Reads every field from a JSON object, strictly: a missing field, a wrong type or a field the
// struct does not have throws InputError naming it. Ranges are checked afterwards (RangeCheck).
class JsonFieldReader {
 public:
  JsonFieldReader(const nlohmann::json& doc, std::string source)
      : source_(std::move(source)), node_(&doc) {}

  void Number(const char* key, double& value, double, double) {
    value = Node(Take(key), path_.At(key)).Number();
  }
  void Integer(const char* key, int& value, int, int) {
    value = Node(Take(key), path_.At(key)).Integer();
  }
  void Text(const char* key, std::string& value) {
    value = Node(Take(key), path_.At(key)).String();
  }
  void Phyllotaxis(const char* key, synth::Phyllotaxis& value) {
    const std::string name = Node(Take(key), path_.At(key)).String();
    if (name == ToString(Phyllotaxis::kOpposite)) {
      value = Phyllotaxis::kOpposite;
    } else if (name == ToString(Phyllotaxis::kAlternate)) {
      value = Phyllotaxis::kAlternate;
    } else {
      throw InputError(source_, path_.At(key),
                       fmt::format("expected \"opposite\" or \"alternate\", got \"{}\"", name));
    }
  }
  template <typename F>
  void Group(const char* key, F&& f) {
    const nlohmann::json& group = Node(Take(key), path_.At(key)).ExpectObject().json();
    Within(group, path_.At(key), f);
  }
  template <typename Container, typename F>
  void List(const char* key, Container& items, int lo, int hi, F&& f) {
    const std::string at = path_.At(key);
    const nlohmann::json& list = Node(Take(key), at).ExpectArray().json();
    if (static_cast<int>(list.size()) < lo || static_cast<int>(list.size()) > hi) {
      throw InputError(source_, at,
                       lo == hi
                           ? fmt::format("expected {} entries, got {}", lo, list.size())
                           : fmt::format("expected {} to {} entries, got {}", lo, hi, list.size()));
    }
    if constexpr (requires { items.resize(size_t{}); }) items.resize(list.size());
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string element_at = Element(at, i);
      Within(Node(list[i], element_at).ExpectObject().json(), element_at, [&] { f(items[i]); });
    }
  }
  // Call after visiting the top level: fails on a field no visitor took.
  void RefuseUnknownFields() { CheckAllTaken(*node_, path_.prefix()); }

 private:
  const nlohmann::json& Take(const char* key) {
    taken_.insert(path_.At(key));
    return Node(*node_, path_.prefix()).Field(key).json();
  }
  template <typename F>
  void Within(const nlohmann::json& object, const std::string& at, F&& f) {
    const nlohmann::json* saved = node_;
    node_ = &object;
    path_.Nest(at, f);
    CheckAllTaken(object, at);
    node_ = saved;
  }
  void CheckAllTaken(const nlohmann::json& object, const std::string& at) {
    for (const auto& [key, value] : object.items()) {
      if (!taken_.contains(Member(at, key)))
        throw InputError(source_, Member(at, key), "unknown field");
    }
  }

  JsonNode Node(const nlohmann::json& value, const std::string& at) const {
    return JsonNode(value, source_, at);
  }

  std::string source_;
  const nlohmann::json* node_;
  PathTracker path_;
  std::set<std::string> taken_;
};

// `patch` over `base` (both JSON objects): objects merge key by key, arrays of objects element
// by element (the patch gives the count; extra entries start from the base's last one), anything
// else is replaced.
void MergeInto(nlohmann::json& base, const nlohmann::json& patch) {
  for (const auto& [key, value] : patch.items()) {
    auto it = base.find(key);
    if (it == base.end()) {
      base[key] = value;  // unknown: kept so the strict reader names it
    } else if (it->is_object() && value.is_object()) {
      MergeInto(*it, value);
    } else if (it->is_array() && value.is_array() && !it->empty() && it->front().is_object()) {
      nlohmann::json merged = nlohmann::json::array();
      for (size_t i = 0; i < value.size(); ++i) {
        nlohmann::json element = (*it)[std::min(i, it->size() - 1)];
        if (value[i].is_object()) {
          MergeInto(element, value[i]);
        } else {
          element = value[i];  // the strict reader names the wrong type
        }
        merged.push_back(std::move(element));
      }
      *it = std::move(merged);
    } else {
      *it = value;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Presets.

AxisShape Shape(double node_spacing_m, double bend_wavelength_m, double bend_angle_deg,
                double tropism_base_per_m, double tropism_tip_per_m) {
  return {node_spacing_m, bend_wavelength_m, bend_angle_deg, tropism_base_per_m, tropism_tip_per_m};
}

BudPattern Buds(double spacing_m, double break_probability, double lateral_preference) {
  return {spacing_m, break_probability, lateral_preference};
}

LevelParams Level(double angle_deg, double angle_spread_deg, double length_ratio,
                  double length_spread, double remaining_length_weight, double start_fraction,
                  AxisShape shape, BudPattern buds) {
  return {angle_deg,
          angle_spread_deg,
          length_ratio,
          length_spread,
          remaining_length_weight,
          start_fraction,
          shape,
          buds};
}

// Green-wood values: USDA Wood Handbook (FPL-GTR-282, Table 5-3a, green) gives red maple
// E = 9.6 GPa, southern magnolia 9.7 GPa; young branch wood is less stiff, so the presets sit a
// little lower. G ~ E / 16 (longitudinal-tangential). Green density is basic density x
// (1 + moisture content ~ 0.8-0.9) plus bark: 850-950 kg/m^3.
SpeciesWood Wood(double youngs_modulus_pa, double density_kg_m3, DampingAnchor low,
                 DampingAnchor high) {
  SpeciesWood wood;
  wood.youngs_modulus_pa = youngs_modulus_pa;
  wood.shear_modulus_pa = youngs_modulus_pa / 16.0;
  wood.density_kg_m3 = density_kg_m3;
  wood.damping = {low, high};
  return wood;
}

SpeciesParams AcerPalmatum() {
  SpeciesParams p;
  p.name = "acer_palmatum";
  p.description =
      "Japanese maple (Acer palmatum), a garden tree of about 3 m in winter: a short trunk that "
      "forks low into a few ascending stems arching out into a wide crown of flat, layered sprays "
      "of fine twigs with drooping tips; opposite, decussate buds.";
  p.height_m = 3.0;
  p.height_spread = 0.1;
  // No extra spread on the trunk radius: the arching stems' longest path already varies it
  // +-20% between seeds.
  p.trunk_base_radius_m = 0.0349;
  p.trunk_radius_spread = 0.0;
  p.longest_path_ratio = 1.32;
  p.min_twig_radius_m = 0.002;
  p.pipe_exponent = 2.5;
  p.shed_shoots_per_m = 1.0;
  p.phyllotaxis = Phyllotaxis::kOpposite;
  p.divergence_angle_deg = 90.0;
  p.phyllotaxis_jitter_deg = 15.0;
  p.crown_peak_position = 0.2;
  p.crown_sharpness = 1.5;
  p.crown_floor = 0.4;
  p.min_branch_length_m = 0.06;
  p.trunk = {.length_fraction = 0.3,
             .lean_deg = 6.0,
             .clear_bole_fraction = 0.5,
             .fork_count = 3,
             .fork_angle_deg = 36.0,
             .fork_angle_spread_deg = 8.0,
             .fork_length_ratio = 1.2,
             .shape = Shape(0.07, 0.8, 8.0, 0.3, 0.3),
             .buds = Buds(0.15, 0.5, 0.0)};
  p.levels = {
      // angle, spread, length ratio, spread, remaining weight, start; shape; buds of the next.
      Level(55, 10, 0.45, 0.2, 1.0, 0.12, Shape(0.07, 0.9, 10, 0.0, -1.0), Buds(0.14, 0.6, 0.6)),
      Level(60, 12, 0.5, 0.25, 0.7, 0.1, Shape(0.06, 0.5, 10, -0.2, -1.0), Buds(0.09, 0.5, 0.7)),
      Level(55, 12, 0.6, 0.25, 0.5, 0.1, Shape(0.05, 0.35, 10, 0.0, -1.5), Buds(0.06, 0.35, 0.7)),
      Level(50, 12, 0.6, 0.3, 0.5, 0.15, Shape(0.045, 0.25, 10, -0.5, -2.0), Buds(0.05, 0.15, 0.5)),
      Level(45, 12, 0.65, 0.3, 0.5, 0.2, Shape(0.04, 0.2, 8, -1.0, -2.5), Buds(0.05, 0.0, 0.0)),
  };
  // Table IV: 1.07-1.50 Hz, damping ratio 0.031-0.060. On a clamped base the wide crown turns
  // before it sways, and the pull swings the links at the sways above the turn (1.5-2.5 Hz). A
  // root plate that tilts lowers the sways and leaves the turn (docs/synth.md, "A root plate for
  // acer_palmatum"): the ratio keeps the most of seeds 1-10's links inside Table IV, and E is the
  // stiffest that keeps them there (frequencies scale as sqrt(E) at a fixed ratio).
  p.wood = Wood(7.7e9, 950.0, {1.0, 0.055}, {6.0, 0.045});
  p.root_plate_stiffness_ratio = 1.5;
  return p;
}

SpeciesParams Magnolia() {
  SpeciesParams p;
  p.name = "magnolia";
  p.description =
      "Saucer magnolia (Magnolia x soulangeana), a young multi-stemmed tree of about 3.5 m in "
      "winter: a low fork into a few thick, upright stems, an open crown of few stout, upturned "
      "branches and thick twigs; alternate buds on a 137.5 degree spiral.";
  p.height_m = 3.9;
  p.height_spread = 0.1;
  p.trunk_base_radius_m = 0.027;
  p.trunk_radius_spread = 0.05;
  p.longest_path_ratio = 1.08;
  p.min_twig_radius_m = 0.003;
  p.pipe_exponent = 2.8;
  p.shed_shoots_per_m = 1.5;
  p.phyllotaxis = Phyllotaxis::kAlternate;
  p.divergence_angle_deg = 137.5;
  p.phyllotaxis_jitter_deg = 12.0;
  p.crown_peak_position = 0.5;
  p.crown_sharpness = 1.0;
  p.crown_floor = 0.5;
  p.min_branch_length_m = 0.06;
  // Multi-stemmed from low down (about 0.6 m), a bare trunk below the fork: the saucer magnolia's
  // usual habit. A fork this low keeps the trunk stiff against the stems, so the stems' own sway
  // is the tree's low modes and a pull on one swings the links near its first mode, as the narrow
  // Table IV range says (docs/synth.md, "Where the rope is tied"); with the fork at 0.3 H the
  // rope went on a trunk lateral below it, whose own 2.7-4.2 Hz mode dominated its links.
  p.trunk = {.length_fraction = 0.15,
             .lean_deg = 5.0,
             .clear_bole_fraction = 0.95,
             .fork_count = 4,
             .fork_angle_deg = 22.0,
             .fork_angle_spread_deg = 6.0,
             .fork_length_ratio = 0.85,
             .shape = Shape(0.07, 1.0, 6.0, 0.4, 0.4),
             .buds = Buds(0.2, 0.4, 0.0)};
  p.levels = {
      Level(40, 10, 0.4, 0.2, 1.0, 0.2, Shape(0.07, 1.0, 7, 0.2, 0.2), Buds(0.15, 0.55, 0.2)),
      Level(42, 10, 0.45, 0.25, 0.6, 0.15, Shape(0.07, 0.6, 8, 0.6, 0.9), Buds(0.1, 0.55, 0.2)),
      Level(40, 10, 0.6, 0.25, 0.5, 0.15, Shape(0.06, 0.4, 8, 1.0, 1.5), Buds(0.07, 0.6, 0.0)),
      Level(35, 10, 0.8, 0.25, 0.3, 0.2, Shape(0.05, 0.3, 8, 1.5, 2.0), Buds(0.06, 0.0, 0.0)),
  };
  // Table IV: 0.72-1.19 Hz, damping ratio 0.023-0.033. The Rayleigh dip between the anchors
  // stays inside that range (0.0231-0.033) over 0.72-4.3 Hz, every link's mode on seeds 1-10.
  p.wood = Wood(6.5e9, 1000.0, {0.72, 0.033}, {4.3, 0.033});
  return p;
}

SpeciesParams AcerRubrum() {
  SpeciesParams p;
  p.name = "acer_rubrum";
  p.description =
      "Red maple (Acer rubrum), a young nursery-grown tree of about 4 m in winter: a central "
      "leader with ascending laterals in an oval, upright crown and slender twigs; opposite, "
      "decussate buds.";
  p.height_m = 4.0;
  p.height_spread = 0.1;
  p.trunk_base_radius_m = 0.03;
  p.trunk_radius_spread = 0.05;
  p.longest_path_ratio = 1.07;
  p.min_twig_radius_m = 0.002;
  p.pipe_exponent = 2.8;
  p.shed_shoots_per_m = 1.0;
  p.phyllotaxis = Phyllotaxis::kOpposite;
  p.divergence_angle_deg = 90.0;
  p.phyllotaxis_jitter_deg = 15.0;
  p.crown_peak_position = 0.35;
  p.crown_sharpness = 1.5;
  p.crown_floor = 0.3;
  p.min_branch_length_m = 0.06;
  p.trunk = {.length_fraction = 0.92,
             .lean_deg = 3.0,
             .clear_bole_fraction = 0.25,
             .fork_count = 0,
             .fork_angle_deg = 30.0,
             .fork_angle_spread_deg = 8.0,
             .fork_length_ratio = 1.0,
             .shape = Shape(0.07, 1.2, 5.0, 0.3, 0.3),
             .buds = Buds(0.12, 0.4, 0.0)};
  p.levels = {
      Level(50, 12, 0.35, 0.2, 1.0, 0.15, Shape(0.07, 0.8, 9, 0.5, 0.3), Buds(0.10, 0.42, 0.4)),
      Level(42, 10, 0.45, 0.25, 0.6, 0.1, Shape(0.06, 0.5, 10, 0.6, 0.6), Buds(0.08, 0.33, 0.3)),
      Level(40, 10, 0.7, 0.25, 0.5, 0.15, Shape(0.05, 0.35, 10, 0.8, 0.8), Buds(0.06, 0.3, 0.2)),
      Level(38, 10, 0.9, 0.25, 0.3, 0.2, Shape(0.045, 0.25, 10, 1.0, 1.0), Buds(0.05, 0.18, 0.0)),
      Level(35, 10, 0.9, 0.25, 0.3, 0.2, Shape(0.04, 0.2, 8, 1.0, 1.0), Buds(0.05, 0.0, 0.0)),
  };
  // Table IV: 0.93-1.50 Hz, damping ratio 0.022-0.056.
  p.wood = Wood(7.5e9, 900.0, {0.9, 0.045}, {6.0, 0.040});
  return p;
}

}  // namespace

WoodProperties SpeciesWood::Properties() const {
  WoodProperties wood;
  wood.youngs_modulus_pa = youngs_modulus_pa;
  wood.shear_modulus_pa = shear_modulus_pa;
  wood.density_kg_m3 = density_kg_m3;
  wood.mature_radius_m = mature_radius_m;
  wood.young_wood_exponent = young_wood_exponent;
  wood.SetRayleighFromRatios(damping[0].frequency_hz, damping[0].damping_ratio,
                             damping[1].frequency_hz, damping[1].damping_ratio);
  return wood;
}

const char* ToString(Phyllotaxis phyllotaxis) {
  return phyllotaxis == Phyllotaxis::kOpposite ? "opposite" : "alternate";
}

std::vector<std::string> SpeciesPresetNames() {
  return {"acer_palmatum", "magnolia", "acer_rubrum"};
}

SpeciesParams SpeciesPreset(const std::string& name) {
  if (name == "acer_palmatum") return AcerPalmatum();
  if (name == "magnolia") return Magnolia();
  if (name == "acer_rubrum") return AcerRubrum();
  throw InputError("species", name,
                   "unknown species preset; expected one of acer_palmatum, magnolia, acer_rubrum");
}

FemOptions SpeciesFemOptions(const SpeciesParams& params) {
  FemOptions options;
  options.root_plate_stiffness_ratio = params.root_plate_stiffness_ratio;
  return options;
}

void ValidateSpecies(const SpeciesParams& params, const std::string& source) {
  RangeCheck check(source);
  VisitSpecies(params, check);
  if (params.trunk.fork_count == 1) {
    throw InputError(source, "trunk.fork_count",
                     "expected 0 (a central leader) or 2 or more co-dominant stems, got 1");
  }
  if (params.wood.damping[0].frequency_hz == params.wood.damping[1].frequency_hz) {
    throw InputError(source, "wood.damping", "expected two different anchor frequencies");
  }
  try {
    params.wood.Properties();
  } catch (const InputError& e) {
    throw InputError(source, "wood.damping", e.what());
  }
}

nlohmann::ordered_json SpeciesToJson(const SpeciesParams& params) {
  nlohmann::ordered_json doc;
  doc["format"] = kSpeciesFormat;
  doc["version"] = kSpeciesFormatVersion;
  JsonWriter writer(&doc);
  VisitSpecies(params, writer);
  return doc;
}

SpeciesParams SpeciesFromJson(const nlohmann::json& doc, const std::string& source) {
  const JsonNode root = JsonNode(doc, source).ExpectObject();
  nlohmann::json full = doc;
  if (doc.contains("base")) {
    const std::string base = root.String("base");
    const auto names = SpeciesPresetNames();
    if (std::find(names.begin(), names.end(), base) == names.end()) {
      root.FailAt("base", fmt::format("unknown preset \"{}\"; expected one of {}", base,
                                      fmt::join(names, ", ")));
    }
    full = nlohmann::json::parse(SpeciesToJson(SpeciesPreset(base)).dump());
    nlohmann::json patch = doc;
    patch.erase("base");
    MergeInto(full, patch);
  }
  const JsonNode merged(full, source);
  if (full.contains("format") && merged.String("format") != std::string(kSpeciesFormat)) {
    merged.FailAt("format", fmt::format("expected \"{}\"", kSpeciesFormat));
  }
  if (full.contains("version") && merged.Integer("version") != kSpeciesFormatVersion) {
    merged.FailAt("version", fmt::format("expected {}", kSpeciesFormatVersion));
  }
  full.erase("format");
  full.erase("version");
  // Young wood's stiffness came after version 2's other fields: a whole file written before it
  // means one modulus for every radius, so the two fields default to that instead of failing.
  if (full.contains("wood") && full["wood"].is_object()) {
    const SpeciesWood one_modulus;
    full["wood"].emplace("mature_radius_m", one_modulus.mature_radius_m);
    full["wood"].emplace("young_wood_exponent", one_modulus.young_wood_exponent);
  }
  // So did the root plate: a file without it has the clamped base it was written for.
  full.emplace("root_plate_stiffness_ratio", 0.0);

  SpeciesParams params;
  JsonFieldReader fields(full, source);
  VisitSpecies(params, fields);
  fields.RefuseUnknownFields();
  ValidateSpecies(params, source);
  return params;
}

SpeciesParams ReadSpeciesJson(const std::filesystem::path& path) {
  const std::string source = path.string();
  return SpeciesFromJson(ParseJson(ReadFile(path), source), source);
}

void WriteSpeciesJson(const SpeciesParams& params, const std::filesystem::path& path) {
  ValidateSpecies(params, path.string());
  WriteFileAtomically(path, SpeciesToJson(params).dump(1) + "\n");
}

}  // namespace simtree::synth
