#include "simtree/synth/species.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

nlohmann::json Parse(const std::string& text) { return nlohmann::json::parse(text); }

TEST(Species, PresetsAreValidAndNamed) {
  const std::vector<std::string> names = SpeciesPresetNames();
  ASSERT_EQ(names, (std::vector<std::string>{"acer_palmatum", "magnolia", "acer_rubrum"}));
  for (const std::string& name : names) {
    const SpeciesParams p = SpeciesPreset(name);
    EXPECT_EQ(p.name, name);
    EXPECT_FALSE(p.description.empty());
    EXPECT_NO_THROW(ValidateSpecies(p, name));
    EXPECT_GE(p.branching_levels(), 4);
    EXPECT_LE(p.branching_levels(), 6);
    // The presets are small trees a camera 1.5-3 m away sees whole: 2.5-4.5 m.
    EXPECT_GE(p.height_m * (1 - p.height_spread), 2.5) << name;
    EXPECT_LE(p.height_m * (1 + p.height_spread), 4.5) << name;
    // Between da Vinci's 2 and Murray's 3, where measured trees fall.
    EXPECT_GE(p.pipe_exponent, 2.0);
    EXPECT_LE(p.pipe_exponent, 3.0);
  }
  EXPECT_EQ(SpeciesPreset("acer_palmatum").phyllotaxis, Phyllotaxis::kOpposite);
  EXPECT_EQ(SpeciesPreset("acer_rubrum").phyllotaxis, Phyllotaxis::kOpposite);
  EXPECT_EQ(SpeciesPreset("magnolia").phyllotaxis, Phyllotaxis::kAlternate);
  EXPECT_DOUBLE_EQ(SpeciesPreset("magnolia").divergence_angle_deg, 137.5);
  EXPECT_NE(test::ErrorOf<InputError>([] { SpeciesPreset("oak"); }).find("acer_rubrum"),
            std::string::npos);
}

// Paper Table IV: each species' natural frequency range and its damping ratio range. The
// Rayleigh damping of a preset must give ratios in that range over the frequencies, and stay in
// 0.02-0.06 for branch modes up to 5 Hz.
TEST(Species, WoodDampingLandsInTableFour) {
  struct Row {
    const char* name;
    double f_lo, f_hi, zeta_lo, zeta_hi;
  };
  for (const Row& row :
       {Row{"acer_palmatum", 1.07, 1.50, 0.031, 0.060}, Row{"magnolia", 0.72, 1.19, 0.023, 0.033},
        Row{"acer_rubrum", 0.93, 1.50, 0.022, 0.056}}) {
    const WoodProperties wood = SpeciesPreset(row.name).wood.Properties();
    EXPECT_NO_THROW(ValidateWood(wood, row.name));
    for (double f = row.f_lo; f <= row.f_hi + 1e-9; f += 0.01) {
      EXPECT_GE(wood.DampingRatioAt(f), row.zeta_lo) << row.name << " " << f;
      EXPECT_LE(wood.DampingRatioAt(f), row.zeta_hi) << row.name << " " << f;
    }
    for (double f = row.f_lo; f <= 5.0; f += 0.05) {
      EXPECT_GE(wood.DampingRatioAt(f), 0.02) << row.name << " " << f;
      EXPECT_LE(wood.DampingRatioAt(f), 0.06) << row.name << " " << f;
    }
    // Green wood: E 5-12 GPa, density 700-1100 kg/m^3.
    EXPECT_GT(wood.youngs_modulus_pa, 5e9);
    EXPECT_LT(wood.youngs_modulus_pa, 12e9);
    EXPECT_GT(wood.density_kg_m3, 700);
    EXPECT_LT(wood.density_kg_m3, 1100);
  }
}

TEST(Species, JsonRoundTripIsExact) {
  const std::filesystem::path dir = test::TempDir();
  for (const std::string& name : SpeciesPresetNames()) {
    SpeciesParams p = SpeciesPreset(name);
    p.height_m = 3.3333333333333335;  // not a short decimal
    WriteSpeciesJson(p, dir / (name + ".json"));
    const SpeciesParams q = ReadSpeciesJson(dir / (name + ".json"));
    EXPECT_EQ(SpeciesToJson(q).dump(), SpeciesToJson(p).dump()) << name;
    EXPECT_EQ(q.height_m, p.height_m);
    EXPECT_EQ(q.levels.size(), p.levels.size());
    EXPECT_EQ(q.phyllotaxis, p.phyllotaxis);
  }
}

TEST(Species, CustomFileChangesFieldsOverABase) {
  const SpeciesParams base = SpeciesPreset("magnolia");
  // The strict reader names the unknown nested field.
  EXPECT_NE(test::ErrorOf<InputError>([] {
              SpeciesFromJson(Parse(R"({"base": "magnolia",
                  "trunk": {"shape": {"lean_deg_is_not_here": 0}}})"),
                              "x.json");
            }).find("trunk.shape.lean_deg_is_not_here: unknown field"),
            std::string::npos);

  const SpeciesParams q = SpeciesFromJson(Parse(R"({
      "base": "magnolia", "name": "tall_magnolia", "height_m": 4.2,
      "trunk": {"fork_count": 3},
      "levels": [{}, {"branching_angle_deg": 60}, {}, {}, {"length_ratio": 0.7}],
      "wood": {"damping": [{}, {"damping_ratio": 0.035}]}})"),
                                          "x.json");
  EXPECT_EQ(q.name, "tall_magnolia");
  EXPECT_EQ(q.height_m, 4.2);
  EXPECT_EQ(q.trunk.fork_count, 3);
  EXPECT_EQ(q.trunk.fork_angle_deg, base.trunk.fork_angle_deg);  // untouched
  ASSERT_EQ(q.levels.size(), 5u);                                // one more level
  EXPECT_EQ(q.levels[1].branching_angle_deg, 60);
  EXPECT_EQ(q.levels[1].length_ratio, base.levels[1].length_ratio);
  EXPECT_EQ(q.levels[4].length_ratio, 0.7);  // the new level starts from the last one
  EXPECT_EQ(q.levels[4].branching_angle_deg, base.levels[3].branching_angle_deg);
  EXPECT_EQ(q.wood.damping[0].frequency_hz, base.wood.damping[0].frequency_hz);
  EXPECT_EQ(q.wood.damping[1].damping_ratio, 0.035);
  EXPECT_EQ(q.description, base.description);
}

TEST(Species, WholeFilesFromBeforeYoungWoodStillLoad) {
  // A whole version-2 file written before the young-wood fields: one modulus, as it meant then.
  nlohmann::json doc = Parse(SpeciesToJson(SpeciesPreset("acer_rubrum")).dump());
  doc["wood"].erase("mature_radius_m");
  doc["wood"].erase("young_wood_exponent");
  const SpeciesParams q = SpeciesFromJson(doc, "old.json");
  EXPECT_EQ(q.wood.young_wood_exponent, 0.0);
  EXPECT_EQ(SpeciesToJson(q).dump(), SpeciesToJson(SpeciesPreset("acer_rubrum")).dump());
  // Given, they are still read strictly.
  doc["wood"]["young_wood_exponent"] = -1.0;
  EXPECT_NE(test::ErrorOf<InputError>([&] {
              SpeciesFromJson(doc, "old.json");
            }).find("wood.young_wood_exponent"),
            std::string::npos);
}

TEST(Species, WholeFilesFromBeforeTheRootPlateAreClamped) {
  nlohmann::json doc = Parse(SpeciesToJson(SpeciesPreset("acer_palmatum")).dump());
  ASSERT_GT(SpeciesPreset("acer_palmatum").root_plate_stiffness_ratio, 0.0);
  doc.erase("root_plate_stiffness_ratio");
  const SpeciesParams q = SpeciesFromJson(doc, "old.json");
  EXPECT_EQ(q.root_plate_stiffness_ratio, 0.0);
  EXPECT_EQ(SpeciesFemOptions(q).root_plate_stiffness_ratio, 0.0);
  // A change over a preset keeps the preset's root plate unless it names one.
  const SpeciesParams over = SpeciesFromJson(Parse(R"({"base": "acer_palmatum"})"), "over.json");
  EXPECT_EQ(SpeciesFemOptions(over).root_plate_stiffness_ratio,
            SpeciesPreset("acer_palmatum").root_plate_stiffness_ratio);
  doc["root_plate_stiffness_ratio"] = -1.0;
  EXPECT_NE(test::ErrorOf<InputError>([&] {
              SpeciesFromJson(doc, "old.json");
            }).find("root_plate_stiffness_ratio"),
            std::string::npos);
}

TEST(Species, StrictErrorsNameTheField) {
  const std::string preset = SpeciesToJson(SpeciesPreset("acer_rubrum")).dump();
  auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json doc = Parse(preset);
    edit(doc);
    return test::ErrorOf<InputError>([&] { SpeciesFromJson(doc, "custom.json"); });
  };
  auto expect_names = [](const std::string& message, const std::string& field) {
    EXPECT_NE(message.find("custom.json"), std::string::npos) << message;
    EXPECT_NE(message.find(field), std::string::npos) << message;
  };
  expect_names(with([](nlohmann::json& d) { d["colour"] = "red"; }), "colour: unknown field");
  expect_names(with([](nlohmann::json& d) { d["levels"][2]["bud_count"] = 3; }),
               "levels[2].bud_count: unknown field");
  expect_names(with([](nlohmann::json& d) { d["height_m"] = "tall"; }),
               "height_m: expected a number");
  expect_names(
      with([](nlohmann::json& d) { d["height_m"] = std::numeric_limits<double>::quiet_NaN(); }),
      "height_m: expected a finite number");
  expect_names(with([](nlohmann::json& d) { d["trunk_base_radius_m"] = -0.04; }),
               "trunk_base_radius_m: expected a number in");
  expect_names(with([](nlohmann::json& d) { d["min_twig_radius_m"] = -0.002; }),
               "min_twig_radius_m");
  expect_names(with([](nlohmann::json& d) {
                 for (int i = 0; i < 4; ++i) d["levels"].push_back(d["levels"][0]);
               }),
               "levels: expected 4 to 6 entries, got 9");
  expect_names(with([](nlohmann::json& d) { d["levels"] = nlohmann::json::array(); }),
               "levels: expected 4 to 6 entries, got 0");
  expect_names(with([](nlohmann::json& d) { d["trunk"]["fork_count"] = 1; }), "trunk.fork_count");
  expect_names(with([](nlohmann::json& d) { d["trunk"]["fork_count"] = 2.5; }),
               "trunk.fork_count: expected an integer");
  expect_names(with([](nlohmann::json& d) { d["phyllotaxis"] = "whorled"; }),
               "phyllotaxis: expected \"opposite\" or \"alternate\"");
  expect_names(with([](nlohmann::json& d) { d["levels"][0]["shape"]["node_spacing_m"] = 5; }),
               "levels[0].shape.node_spacing_m");
  expect_names(with([](nlohmann::json& d) { d.erase("pipe_exponent"); }), "pipe_exponent: missing");
  expect_names(with([](nlohmann::json& d) { d["wood"]["damping"].push_back({}); }),
               "wood.damping: expected 2 entries, got 3");
  // Damping that rises steeply between the anchors needs a negative Rayleigh coefficient.
  expect_names(with([](nlohmann::json& d) {
                 d["wood"]["damping"] = Parse(R"([{"frequency_hz": 1, "damping_ratio": 0.01},
                                                 {"frequency_hz": 2, "damping_ratio": 0.05}])");
               }),
               "wood.damping");
  expect_names(with([](nlohmann::json& d) { d["version"] = 1; }), "version");
  expect_names(with([](nlohmann::json& d) { d["base"] = "oak"; }), "base: unknown preset");
  expect_names(with([](nlohmann::json& d) { d["levels"][1] = 3; }),
               "levels[1]: expected an object");
  EXPECT_NE(test::ErrorOf<InputError>([] {
              SpeciesFromJson(Parse("[1, 2]"), "custom.json");
            }).find("expected an object"),
            std::string::npos);
}

TEST(Species, FilesThatCannotBeReadAreRefused) {
  const std::filesystem::path dir = test::TempDir();
  EXPECT_THROW(ReadSpeciesJson(dir / "missing.json"), Error);
  test::WriteText(dir / "empty.json", "");
  EXPECT_THROW(ReadSpeciesJson(dir / "empty.json"), InputError);
  test::WriteText(dir / "broken.json", "{\"base\": \"magnolia\",");
  EXPECT_NE(test::ErrorOf<InputError>([&] { ReadSpeciesJson(dir / "broken.json"); }).find("line 1"),
            std::string::npos);
  // Writing refuses an invalid struct and leaves nothing behind.
  SpeciesParams p = SpeciesPreset("magnolia");
  p.levels.resize(3);
  EXPECT_THROW(WriteSpeciesJson(p, dir / "out.json"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
}

}  // namespace
}  // namespace simtree::synth
