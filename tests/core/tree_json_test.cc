#include "simtree/core/tree_json.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/tree_fixtures.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::string& text) {
  try {
    TreeFromJson(ParseJson(text, "t.json"), "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A valid document to break one field at a time.
nlohmann::json ValidDoc() {
  return nlohmann::json::parse(TreeToJson(test::SmallTreeWithMaterials()).dump());
}

TEST(TreeJson, RoundTripIsExact) {
  const Tree tree = test::SmallTreeWithMaterials();
  const auto dir = test::TempDir();
  WriteTreeJson(tree, dir / "a.json");
  const Tree back = ReadTreeJson(dir / "a.json");
  WriteTreeJson(back, dir / "b.json");
  EXPECT_EQ(test::ReadText(dir / "a.json"), test::ReadText(dir / "b.json"));
  ASSERT_EQ(back.size(), tree.size());
  for (int i = 0; i < tree.size(); ++i) {
    const Branch& a = tree.branches[i];
    const Branch& b = back.branches[i];
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (size_t n = 0; n < a.nodes.size(); ++n) {
      EXPECT_EQ(a.nodes[n].position, b.nodes[n].position);  // bit-exact
      EXPECT_EQ(a.nodes[n].radius, b.nodes[n].radius);
    }
    EXPECT_EQ(a.frame.u, b.frame.u);
    EXPECT_EQ(a.material->modes[1].frequency_hz, b.material->modes[1].frequency_hz);
    EXPECT_EQ(a.material->mass_kg, b.material->mass_kg);
    EXPECT_EQ(a.material->source, b.material->source);
  }
  EXPECT_EQ(back.markers.size(), 2u);
  EXPECT_EQ(back.markers[1].parent, 0);
  EXPECT_EQ(back.metadata.species, "test");
}

TEST(TreeJson, MissingFramesAreComputed) {
  nlohmann::json doc = ValidDoc();
  for (auto& b : doc["branches"]) b.erase("frame");
  const Tree t = TreeFromJson(doc, "t.json");
  EXPECT_TRUE(t.branches[1].frame.v.isApprox(Eigen::Vector3d(1, 0, 1).normalized()));
}

TEST(TreeJson, ErrorsNameFileAndField) {
  nlohmann::json doc = ValidDoc();
  doc["branches"][2]["nodes"][1][3] = -0.5;
  EXPECT_EQ(ErrorOf(doc.dump()),
            "t.json: branches[2].nodes[1].radius: expected a positive radius, got -0.5");

  doc = ValidDoc();
  doc["version"] = 2;
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("t.json: version: expected 1"));

  doc = ValidDoc();
  doc["format"] = "something.else";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("format: expected \"simtree.tree\""));

  doc = ValidDoc();
  doc["branches"][1]["nodes"][0] = {1, 2, 3};
  EXPECT_THAT(ErrorOf(doc.dump()),
              HasSubstr("branches[1].nodes[0]: expected 4 numbers [x, y, z, radius]"));

  doc = ValidDoc();
  doc["branches"][1].erase("parent");
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("branches[1].parent: missing"));

  doc = ValidDoc();
  doc["branches"][1]["material"]["modes"][0]["kind"] = "wobble";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("material.modes[0].kind: expected \"bend_u\""));

  doc = ValidDoc();
  doc["branches"][1]["nodes"][0][0] = nullptr;  // what NaN becomes when JSON libraries write it
  EXPECT_THAT(ErrorOf(doc.dump()),
              HasSubstr("branches[1].nodes[0][0]: expected a number, got null"));

  doc = ValidDoc();
  doc["metadata"]["units"] = "mm";
  EXPECT_THAT(ErrorOf(doc.dump()), HasSubstr("metadata.units: expected \"m\""));
}

TEST(TreeJson, SyntaxErrorsGiveLineAndColumn) {
  std::string text = ValidDoc().dump(1);
  const size_t at = text.find("\"parent\"");
  text.insert(at, "NaN, ");
  EXPECT_THAT(ErrorOf(text), HasSubstr("t.json: line "));
  EXPECT_THAT(ErrorOf(""), HasSubstr("the file is empty"));
  EXPECT_THAT(ErrorOf(text.substr(0, text.size() / 2)), HasSubstr("invalid JSON"));
}

// A number beyond a double's range is nlohmann's out_of_range, not a parse_error; it escaped as
// such (found by fuzz/markers_json, fuzz/regressions/markers_json/number_overflow.json).
TEST(TreeJson, NumbersBeyondADoubleAreInputErrors) {
  EXPECT_THAT(ErrorOf("44644404444E4444"),
              HasSubstr("t.json: invalid JSON (number overflow parsing '44644404444E4444')"));
  std::string text = ValidDoc().dump(1);
  text.insert(text.find("\"parent\"") + 9, "1E999, \"x\": ");
  EXPECT_THAT(ErrorOf(text), HasSubstr("number overflow parsing '1E999'"));
  EXPECT_THAT(ErrorOf(test::ReadText(std::filesystem::path(SIMTREE_SOURCE_DIR) /
                                     "fuzz/regressions/markers_json/number_overflow.json")),
              HasSubstr("number overflow"));
}

TEST(TreeJson, RefusesToWriteAnInvalidTreeAndLeavesNoFile) {
  Tree t = test::SmallTree();
  t.branches[1].nodes[1].radius = 0.0;
  const auto dir = test::TempDir();
  EXPECT_THROW(WriteTreeJson(t, dir / "bad.json"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace simtree
