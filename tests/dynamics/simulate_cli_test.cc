// `simtree simulate` end to end on the authors' tree01 with their tree_parameters.txt: the glTF
// opens with the right node and frame counts, and the pulled branch's marker oscillates at the
// parameter file's frequency after release. And bad input: a clear error and no output.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "simtree/core/legacy_format.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/recorders.h"
#include "test_util.h"

namespace simtree::dynamics {
namespace {

using ::testing::HasSubstr;

std::string Demo(const std::string& file) {
  return test::SharedData("authors-demo/" + file).string();
}

struct Track {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> p;
};

// marker id -> its rows, from a trajectory CSV.
std::map<int, Track> ReadTracks(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# simtree.trajectories v1 frame=world units=m");
  std::getline(in, line);
  EXPECT_EQ(line, "frame,time_s,marker,x,y,z,valid");
  std::map<int, Track> tracks;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    int frame = 0, marker = 0, valid = 0;
    double t = 0, x = 0, y = 0, z = 0;
    row >> frame >> t >> marker >> x >> y >> z >> valid;
    EXPECT_EQ(valid, 1);
    tracks[marker].t.push_back(t);
    tracks[marker].p.emplace_back(x, y, z);
  }
  return tracks;
}

// The frequency of the strongest oscillation of a track after `from_s`: the displacement along
// its main direction, Hann-windowed, its DFT searched on a 0.001 Hz grid.
double DominantFrequency(const Track& track, double from_s) {
  std::vector<Eigen::Vector3d> p;
  for (size_t i = 0; i < track.t.size(); ++i) {
    if (track.t[i] >= from_s) p.push_back(track.p[i]);
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : p) mean += x;
  mean /= p.size();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& x : p) cov += (x - mean) * (x - mean).transpose();
  const Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
  const double dt = track.t[1] - track.t[0];
  const size_t n = p.size();
  double best = 0, best_f = 0;
  for (double f = 0.3; f <= 5.0; f += 0.001) {
    double re = 0, im = 0;
    for (size_t i = 0; i < n; ++i) {
      const double w = 0.5 - 0.5 * std::cos(kTwoPi * i / (n - 1));
      const double x = w * (p[i] - mean).dot(axis);
      re += x * std::cos(kTwoPi * f * i * dt);
      im -= x * std::sin(kTwoPi * f * i * dt);
    }
    if (re * re + im * im > best) {
      best = re * re + im * im;
      best_f = f;
    }
  }
  return best_f;
}

TEST(SimulateCli, AuthorsTreePulledAndReleasedRingsAtItsFrequency) {
  const auto dir = test::TempDir();
  const auto out = dir / "sim01";
  const int branch = 1;  // a first-level branch of tree01
  const auto r = test::RunCli("-q simulate " + Demo("tree_model/tree01.txt") + " --material-file " +
                              Demo("tree_parameters.txt") + " --pull " + std::to_string(branch) +
                              " --force 200 --hold 1 --release 3 --duration 23 --fps 30 --out " +
                              out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file :
       {"nodes.bin", "markers.csv", "markers.json", "animation.glb", "simulation.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  const Tree tree = ReadLegacyTree(Demo("tree_model/tree01.txt"));
  const int frames = 23 * 30 + 1;

  // The glTF opens; one joint per node, one key per frame.
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (out / "animation.glb").string()))
      << err;
  ASSERT_EQ(model.skins.size(), 1u);
  EXPECT_EQ(model.skins[0].joints.size(), static_cast<size_t>(tree.NodeCount()));
  ASSERT_EQ(model.animations.size(), 1u);
  for (const tinygltf::AnimationSampler& s : model.animations[0].samplers) {
    ASSERT_EQ(model.accessors[s.input].count, static_cast<size_t>(frames));
    ASSERT_EQ(model.accessors[s.output].count, static_cast<size_t>(frames));
  }
  EXPECT_NEAR(model.accessors[model.animations[0].samplers[0].input].maxValues[0], 23.0, 1e-4);

  const NodeFrames nodes = ReadNodeFrames(out / "nodes.bin");
  EXPECT_EQ(nodes.node_count, tree.NodeCount());
  EXPECT_EQ(nodes.frame_count, frames);

  // The pulled point's marker rings at the parameter file's frequency for that branch.
  const auto params = ParseLegacyParameters(test::ReadText(Demo("tree_parameters.txt")), "p");
  const double expected = params[branch].frequency_hz;
  const std::string markers = test::ReadText(out / "markers.json");
  ASSERT_THAT(markers, HasSubstr("\"pull\""));
  const std::map<int, Track> tracks = ReadTracks(out / "markers.csv");
  const Track& pulled = tracks.rbegin()->second;  // the pull marker comes last
  ASSERT_EQ(pulled.t.size(), static_cast<size_t>(frames));
  const double found = DominantFrequency(pulled, 3.5);
  EXPECT_NEAR(found, expected, 0.01 * expected) << "FFT peak " << found << " Hz";
  // It moved: pulled down by centimetres, then swinging.
  double travel = 0;
  for (const auto& p : pulled.p) travel = std::max(travel, (p - pulled.p.front()).norm());
  EXPECT_GT(travel, 0.01);
}

TEST(SimulateCli, BadInputGivesAClearErrorAndNoOutput) {
  const auto dir = test::TempDir();
  const auto out = dir / "out";
  const std::string tree = Demo("tree_model/tree01.txt");
  const std::string params = " --material-file " + Demo("tree_parameters.txt");
  struct Case {
    std::string args, message;
  };
  std::string zero = test::ReadText(Demo("tree_parameters.txt"));
  zero.replace(zero.find("1.6 0.02 5000"), 13, "0 0.02 5000");
  test::WriteText(dir / "zero.txt", zero);
  std::string nan = test::ReadText(Demo("tree_parameters.txt"));
  nan.replace(nan.find("1.6 0.02 5000"), 13, "1.6 nan 5000");
  test::WriteText(dir / "nan.txt", nan);
  const std::vector<Case> cases = {
      {tree + params + " --pull 999 --force 10", "expected a branch id in [0, 94], got 999"},
      {tree + params + " --pull 3@99 --force 10", "arc length"},
      {tree + params + " --pull 3 --force 10 --duration -1", "duration"},
      {tree + params + " --pull 3 --force 10 --hold 2 --release 1", "release"},
      {tree + params + " --pull 3 --force -5", "tension"},
      {tree + params + " --pull 3", "--force"},
      {tree + params + " --pull x --force 1", "BRANCH"},
      {tree + params + " --fps 0", "frame rate"},
      {tree + " --pull 3 --force 10", "material"},
      {tree + " --material-file " + (dir / "zero.txt").string() + " --pull 3 --force 10",
       "frequency"},
      {tree + " --material-file " + (dir / "nan.txt").string() + " --pull 3 --force 10",
       "finite number"},
  };
  for (const Case& c : cases) {
    const auto r = test::RunCli("-q simulate " + c.args + " --out " + out.string());
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << c.args;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
  }
  // Never over an input.
  const auto r = test::RunCli("-q simulate " + tree + params + " --out " + Demo("tree_model"));
  EXPECT_NE(r.exit_code, 0);
}

TEST(SimulateCli, HelpTeaches) {
  const auto r = test::RunCli("simulate --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("Examples:"));
  EXPECT_THAT(r.output, HasSubstr("--pull"));
  EXPECT_THAT(r.output, HasSubstr("--wind"));
}

}  // namespace
}  // namespace simtree::dynamics
