// `simtree identify` and `simtree build` as a user meets them.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/tree_json.h"
#include "simtree/identification/detail/test_signals.h"
#include "simtree/identification/materials_file.h"
#include "simtree/tracking/tracker_error.h"
#include "test_util.h"
#include "tree_fixture.h"

namespace simtree::identification {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A pull test folder: tracks/trajectories.csv and markers.json (markers on branches 0, 1, 2).
fs::path WritePullTest(const fs::path& dir) {
  SyntheticMarkerTree tree;
  tree.root_motion[0] = {{0.95, 0.03, 0.01, 0.0}};
  tree.links.resize(2);
  tree.links[0].theta_u = {{1.15, 0.035, 0.1, 0.0}};
  tree.links[0].theta_w = {{1.25, 0.03, 0.05, 0.0}};
  tree.links[1].rest_direction = {-1, -0.5, 0};
  tree.links[1].theta_u = {{1.4, 0.045, 0.1, 0.0}};
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(tree, 30, 1.5, 10, &markers);
  for (int m = 0; m < 3; ++m) markers[m].branch = m;
  fs::create_directories(dir / "tracks");
  WriteTrajectoriesCsv(tracking::SimulateTrackerError(t, {}), dir / "tracks" / "trajectories.csv");
  WriteMarkersJson(markers, dir / "markers.json");
  return dir;
}

TEST(IdentifyCli, IdentifiesWritesPlotsAndBuildsASimulationReadyTree) {
  const fs::path dir = WritePullTest(test::TempDir());
  auto r =
      test::RunCli("-q identify " + (dir / "tracks").string() + " --links " +
                   (dir / "markers.json").string() + " --out " + (dir / "materials.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Ranges (paper Table IV)"));
  EXPECT_THAT(r.output, HasSubstr("half_power_fft"));
  EXPECT_TRUE(fs::exists(dir / "materials_spectra" / "M0-M1.png"));
  EXPECT_TRUE(fs::exists(dir / "materials_spectra" / "M0.png"));
  const MaterialsFile m = ReadMaterialsJson(dir / "materials.json");
  ASSERT_EQ(m.links.size(), 3u);
  EXPECT_NEAR(m.links[1].value.frequency_hz, 1.15, 0.0115);
  EXPECT_EQ(m.branches.size(), 3u);

  WriteTreeJson(test::IdentificationTree(), dir / "static.json");
  r = test::RunCli("-q build " + (dir / "static.json").string() + " --materials " +
                   (dir / "materials.json").string() + " --out " + (dir / "ready.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Tree ready = ReadTreeJson(dir / "ready.json");
  EXPECT_TRUE(ready.IsSimulationReady());
  EXPECT_EQ(ready.branches[1].material->source, MaterialSource::kMeasured);
  EXPECT_EQ(ready.branches[4].material->source, MaterialSource::kInterpolated);
  EXPECT_THAT(r.output, HasSubstr("measured"));
}

TEST(IdentifyCli, BadInputsSayWhatIsWrongAndWriteNothing) {
  const fs::path dir = WritePullTest(test::TempDir());
  const std::string tracks = (dir / "tracks").string();
  const std::string out = (dir / "m.json").string();
  // A marker list linking to a marker that is not in it.
  test::WriteText(dir / "bad_links.json",
                  R"({"format": "simtree.markers", "version": 1, "markers": [
                      {"id": 0, "parent": -1}, {"id": 1, "parent": 8}]})");
  auto r = test::RunCli("identify " + tracks + " --links " + (dir / "bad_links.json").string() +
                        " --out " + out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("links to marker 8, which is not in the list"));
  // No links at all.
  r = test::RunCli("identify " + tracks + " --out " + out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("no marker links"));
  // Truncated trajectories.
  test::WriteText(dir / "cut.csv",
                  "# simtree.trajectories v1 frame=camera units=m\nframe,time_s\n");
  r = test::RunCli("identify " + (dir / "cut.csv").string() + " --links " +
                   (dir / "markers.json").string() + " --out " + out);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("line 2: expected the header"));
  // Writing over an input.
  r = test::RunCli("identify " + tracks + " --links " + (dir / "markers.json").string() +
                   " --out " + (dir / "markers.json").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "m_spectra"));
  // Build without any measured value.
  test::WriteText(
      dir / "empty.json",
      R"({"format": "simtree.materials", "version": 1, "estimator": "damped_sinusoid_fit",
          "links": []})");
  WriteTreeJson(test::IdentificationTree(), dir / "static.json");
  r = test::RunCli("build " + (dir / "static.json").string() + " -m " +
                   (dir / "empty.json").string() + " -o " + (dir / "ready.json").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("nothing to build from"));
  EXPECT_FALSE(fs::exists(dir / "ready.json"));
}

}  // namespace
}  // namespace simtree::identification
