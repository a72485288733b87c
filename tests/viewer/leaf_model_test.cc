// The authors' leaf models: both shipped folders read, the blade's upper side faces +z, and every
// kind of broken file is an InputError naming the file and line.

#include "simtree/viewer/detail/leaf_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

constexpr const char* kSmallLeaf =
    "PetioleVerNum=2 LeafVerNum=3 LeafFacesNum=1 Scale=0.5\n"
    "0 0 0 0 0.01\n"
    "1 0.2 0 0 0.01\n"
    "0 0.2 0 0 0 0\n"
    "1 1.2 0 0 1 0\n"
    "2 0.6 0 0.4 0.5 1\n"
    "0 0 1 2\n";

std::string ParseError(const std::string& text) {
  try {
    ParseLeafModel(text, "leaf.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LeafModel, ReadsBothAuthorsLeaves) {
  for (const char* name : {"apple_leaf", "maple_leaf"}) {
    const LeafModel m =
        ReadLeafModel(test::SharedData("authors-demo/leaf_model") / name / "leaf.txt");
    EXPECT_GE(m.vertices.size(), 80u) << name;
    EXPECT_EQ(m.uvs.size(), m.vertices.size());
    EXPECT_GE(m.triangles.size(), 90u);
    EXPECT_GE(m.petiole_points.size(), 5u);
    // Mean face normal: the upper side looks up once the demo's Y-up axes are turned Z-up.
    Eigen::Vector3f n = Eigen::Vector3f::Zero();
    for (const auto& t : m.triangles) {
      n += (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    }
    EXPECT_GT(n.normalized().z(), 0.5f) << name;
    for (const auto& uv : m.uvs) {
      EXPECT_GE(uv.x(), 0.0f);
      EXPECT_LE(uv.x(), 1.0f);
    }
  }
}

TEST(LeafModel, AppliesScaleAndTurnsAxes) {
  const LeafModel m = ParseLeafModel(kSmallLeaf, "leaf.txt");
  EXPECT_FLOAT_EQ(m.scale, 0.5f);
  // Demo (x, y, z) -> (x, -z, y), times Scale.
  EXPECT_TRUE(m.vertices[2].isApprox(Eigen::Vector3f(0.3f, -0.2f, 0.0f)));
  EXPECT_FLOAT_EQ(m.petiole_radii[0], 0.005f);
  EXPECT_NEAR(m.Length(), 0.6f, 1e-6f);  // (1.2, 0, 0) * 0.5 from the petiole base
  // Winding reversed: counter-clockwise seen from +z.
  EXPECT_EQ(m.triangles[0], Eigen::Vector3i(0, 2, 1));
}

TEST(LeafModel, BadFilesNameTheLine) {
  EXPECT_THAT(ParseError(""), HasSubstr("expected the header"));
  EXPECT_THAT(ParseError("Petioles=2\n"), HasSubstr("line 1"));
  std::string text = kSmallLeaf;
  EXPECT_THAT(ParseError(text.replace(text.find("Scale=0.5"), 9, "Scale=-1")),
              HasSubstr("Scale: expected > 0"));
  text = kSmallLeaf;
  EXPECT_THAT(ParseError(text.replace(text.find("0 0 1 2"), 7, "0 0 1 7")),
              HasSubstr("line 7: expected vertex indices in [0, 2], got 7"));
  text = kSmallLeaf;
  EXPECT_THAT(ParseError(text.replace(text.find("1 1.2 0 0 1 0"), 13, "1 1.2 nan 0 1 0")),
              HasSubstr("line 5: expected a finite number"));
  text = kSmallLeaf;
  EXPECT_THAT(ParseError(text.substr(0, text.rfind("0 0 1 2"))), HasSubstr("expected 6 lines"));
  text = kSmallLeaf;
  EXPECT_THAT(ParseError(text.replace(text.find("0 0 0 0 0.01"), 12, "0 0 0 0 -0.01")),
              HasSubstr("line 2: expected a radius >= 0"));
  EXPECT_THAT(ParseError(std::string(kSmallLeaf) + "extra line\n"), HasSubstr("lines after"));
}

TEST(LeafModel, CorruptTextureOrMissingFileIsAnInputErrorNamingIt) {
  const auto dir = test::TempDir();
  const auto folder = test::CopyAppleLeaf(dir);
  EXPECT_NO_THROW(LoadLeafAssets(folder));
  test::WriteText(folder / "leafup.bmp", "BM this is not a bitmap");
  try {
    LoadLeafAssets(folder);
    FAIL() << "a corrupt texture was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("leafup.bmp"));
  }
  std::filesystem::remove(folder / "leaf.txt");
  EXPECT_THROW(LoadLeafAssets(folder), InputError);
  EXPECT_THROW(LoadLeafAssets(dir / "nowhere"), InputError);
}

}  // namespace
}  // namespace simtree::viewer
