// The catalogue of bad inputs (docs/fuzzing.md), end to end through the CLI: each case exits
// non-zero with a message naming the file and the line, field or unit, leaves no output behind
// (not even a temporary file) and leaves its inputs byte for byte as they were.

#include <sys/mount.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/io/trajectories.h"
#include "support/open3d_folder_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Every file under `root` with its bytes: what a refused run must leave as it was.
std::map<fs::path, std::string> Snapshot(const fs::path& root) {
  std::map<fs::path, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) files[entry.path()] = test::ReadText(entry.path());
  }
  return files;
}

// Runs `simtree <args>` with the inputs under `dir`; expects a refusal whose message holds each
// of `expected`, and `dir` exactly as before (inputs unchanged, nothing written).
void ExpectRefused(const fs::path& dir, const std::string& args,
                   const std::vector<std::string>& expected) {
  const auto before = Snapshot(dir);
  const test::CliResult r = test::RunCli(args);
  EXPECT_NE(r.exit_code, 0) << r.output;
  for (const std::string& text : expected) EXPECT_THAT(r.output, HasSubstr(text));
  EXPECT_EQ(Snapshot(dir), before) << "the run changed or left files in " << dir;
}

// Appends, not a + chain: GCC 12 warns falsely (-Wstringop-overflow) on the chain.
std::string Path(const fs::path& p) {
  std::string quoted = "\"";
  quoted += p.string();
  quoted += '"';
  return quoted;
}

// A thin standing cylinder of points, `height` tall in the file's units.
open3d::geometry::PointCloud Stem(double height, double radius) {
  open3d::geometry::PointCloud cloud;
  for (int i = 0; i < 400; ++i) {
    const double a = 0.7 * i;
    cloud.points_.emplace_back(radius * std::cos(a), radius * std::sin(a), height * i / 399.0);
  }
  return cloud;
}

std::string Reconstruct(const fs::path& cloud, const fs::path& dir) {
  return "reconstruct " + Path(cloud) + " --out " + Path(dir / "tree.json");
}

constexpr const char* kTwoMarkers = R"({"format": "simtree.markers", "version": 1, "markers": [
    {"id": 0, "parent": -1}, {"id": 1, "parent": 0}]})";

// A pull test of two markers over two frames, and `markers` as its markers.json.
void WritePullTest(const fs::path& dir, const std::string& markers) {
  Trajectories t;
  t.tracks.resize(2);
  t.tracks[0].marker = 0;
  t.tracks[1].marker = 1;
  for (int f = 0; f < 2; ++f) {
    t.AddFrame(f, f / 30.0, {{0, 0, 1}, {0.1, 0.2, 1}}, {true, true});
  }
  WriteTrajectoriesCsv(t, dir / "trajectories.csv");
  test::WriteText(dir / "markers.json", markers);
}

std::string Identify(const fs::path& dir) {
  return "identify " + Path(dir / "trajectories.csv") + " --out " + Path(dir / "materials.json");
}

TEST(BadInputCli, EmptyCloud) {
  const fs::path dir = test::TempDir();
  test::WriteText(dir / "empty.ply", "");
  ExpectRefused(dir, Reconstruct(dir / "empty.ply", dir), {"empty.ply: the file is empty"});
}

TEST(BadInputCli, TruncatedCloud) {
  const fs::path dir = test::TempDir();
  WritePointCloud(Stem(2, 0.05), dir / "stem.ply");
  std::string bytes = test::ReadText(dir / "stem.ply");
  bytes.resize(bytes.size() - 100);
  test::WriteText(dir / "stem.ply", bytes);
  ExpectRefused(dir, Reconstruct(dir / "stem.ply", dir), {"stem.ply", "vertex"});
}

TEST(BadInputCli, NanAndInfinityInACloudAndInTrajectories) {
  const fs::path dir = test::TempDir();
  test::WriteText(dir / "nan.xyz", "nan 0 1\n0 inf 2\n-inf 1 nan\n");
  ExpectRefused(dir, Reconstruct(dir / "nan.xyz", dir), {"nan.xyz", "finite"});
  // A valid row with an infinite coordinate: the reader names the line.
  WritePullTest(dir, kTwoMarkers);
  test::WriteText(dir / "trajectories.csv",
                  std::string(kTrajectoriesFirstLine) + "\n" + kTrajectoriesHeader +
                      "\n0,0.0,0,0.1,0.2,1.0,1\n0,0.0,1,0.1,0.2,1.0,1\n"
                      "1,0.033,0,0.1,inf,1.0,1\n1,0.033,1,0.1,0.2,1.0,1\n");
  ExpectRefused(dir, Identify(dir), {"trajectories.csv: line 5"});
}

TEST(BadInputCli, MillimetresForMetresNameTheUnitAndTheFix) {
  const fs::path dir = test::TempDir();
  WritePointCloud(Stem(3000, 50), dir / "tree_mm.xyz");  // a 3 m stem written in millimetres
  ExpectRefused(dir, Reconstruct(dir / "tree_mm.xyz", dir),
                {"tree_mm.xyz: units", "millimetres", "--scale 0.001"});
}

TEST(BadInputCli, ACloudOfOnePoint) {
  const fs::path dir = test::TempDir();
  test::WriteText(dir / "one.xyz", "0.1 0.2 1.5\n");
  ExpectRefused(dir, Reconstruct(dir / "one.xyz", dir), {"one.xyz: shape", "no vertical"});
}

TEST(BadInputCli, ABillionPointHeaderWithNoData) {
  const fs::path dir = test::TempDir();
  test::WriteText(dir / "billion.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                  "property float x\nproperty float y\nproperty float z\nend_header\n");
  ExpectRefused(dir, Reconstruct(dir / "billion.ply", dir), {"billion.ply", "1000000000"});
}

TEST(BadInputCli, DuplicateMarkerIds) {
  const fs::path dir = test::TempDir();
  WritePullTest(dir, R"({"format": "simtree.markers", "version": 1, "markers": [
    {"id": 0, "parent": -1}, {"id": 0, "parent": -1}]})");
  ExpectRefused(dir, Identify(dir), {"markers.json: markers[1].id", "appears twice"});
}

TEST(BadInputCli, ACycleInMarkerLinks) {
  const fs::path dir = test::TempDir();
  WritePullTest(dir, R"({"format": "simtree.markers", "version": 1, "markers": [
    {"id": 0, "parent": 1}, {"id": 1, "parent": 0}]})");
  ExpectRefused(dir, Identify(dir), {"markers.json: markers[0].parent", "form a cycle"});
}

TEST(BadInputCli, ADirectoryWhereAFileIsExpected) {
  const fs::path dir = test::TempDir();
  fs::create_directories(dir / "tree.json");
  ExpectRefused(dir, "convert " + Path(dir / "tree.json") + " " + Path(dir / "out.json"),
                {"tree.json"});
  fs::create_directories(dir / "cloud.ply");
  ExpectRefused(dir, Reconstruct(dir / "cloud.ply", dir), {"cloud.ply"});
}

TEST(BadInputCli, BranchScoresForATreeThatIsNotTheTruths) {
  const fs::path dir = test::TempDir();
  WritePullTest(dir, kTwoMarkers);
  ASSERT_EQ(test::RunCli(Identify(dir)).exit_code, 0);  // statuses only: two frames
  const fs::path demo = test::SharedData("authors-demo/tree_model");
  fs::create_directories(dir / "gt");
  ASSERT_EQ(test::RunCli("convert " + Path(demo / "tree01.txt") + " " + Path(dir / "gt/tree.json"))
                .exit_code,
            0);
  ASSERT_EQ(test::RunCli("convert " + Path(demo / "tree02.txt") + " " + Path(dir / "other.json"))
                .exit_code,
            0);
  ModalTruth truth;
  truth.branches = {{0, 1.0, 0.03}};
  WriteModalTruth(truth, dir / "gt/modal.json");
  ExpectRefused(dir,
                "eval identification " + Path(dir / "materials.json") + " --gt " + Path(dir) +
                    " --tree " + Path(dir / "other.json") + " --json " + Path(dir / "scores.json"),
                {"other.json", "not built on the truth's tree", "148 branches", "has 95"});
}

TEST(BadInputCli, AnUnwritableOutputFolder) {
  const fs::path dir = test::TempDir();
  const fs::path tree = test::SharedData("authors-demo/tree_model/tree01.txt");
  const std::string tree_bytes = test::ReadText(tree);
  // /proc refuses new entries even to root (a read-only folder would not stop root).
  const fs::path out = "/proc/1/simtree-out/tree.json";
  ExpectRefused(dir, "convert " + Path(tree) + " " + Path(out), {"/proc/1/simtree-out"});
  EXPECT_EQ(test::ReadText(tree), tree_bytes);
  // A file where the output folder should be.
  test::WriteText(dir / "not_a_folder", "x");
  ExpectRefused(dir, "convert " + Path(tree) + " " + Path(dir / "not_a_folder/tree.json"),
                {"not_a_folder"});
}

TEST(BadInputCli, AnOutputFolderThatIsAnInput) {
  const fs::path dir = test::TempDir();
  const fs::path recording = test::WriteOpen3dFolder(dir / "dataset", 2, "intrinsic.json");
  ExpectRefused(dir, "capture-from --pull " + Path(recording) + " --out " + Path(recording),
                {"dataset"});
  ExpectRefused(dir,
                "capture-from --pull " + Path(recording) + " --out " + Path(recording / "capture"),
                {"dataset"});
}

// A 64 KiB tmpfs (root only: skipped where mounting is not allowed) that the mesh of the
// authors' tree does not fit.
TEST(BadInputCli, ADiskThatFillsMidWrite) {
  const fs::path dir = test::TempDir();
  const fs::path small = dir / "small";
  fs::create_directories(small);
  if (::mount("simtree-test", small.c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root): " << std::strerror(errno);
  }
  const fs::path tree = test::SharedData("authors-demo/tree_model/tree01.txt");
  const auto r = test::RunCli("mesh " + Path(tree) + " --out " + Path(small / "tree.ply"));
  const bool empty = fs::is_empty(small);
  ::umount(small.c_str());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("tree.ply"));
  EXPECT_TRUE(empty) << "a partial mesh or a temporary file was left on the full disk";
}

}  // namespace
}  // namespace simtree
