// The tracker's start from a tree's markers and the pull camera's pose: on a drawn stream whose
// truth is known, with the pose exact, off by a registration's error (more than the tapes'
// spacing in the image), off by more than the gate, and with bad inputs.

#include "simtree/tracking/init_from_tree.h"

#include <filesystem>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "drawn_stream.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/io/ground_truth.h"
#include "simtree/tracking/camera_pose_file.h"
#include "simtree/tracking/detail/projection_match.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::tracking {
namespace {

using ::testing::HasSubstr;

// A row of four tapes 6 cm apart (about 9 px at 1.5 m with f = 217 px) and two off the row, at
// several depths: a pose error of 1.5 degrees moves every projection further than the row's
// spacing, so each projection's nearest blob is a neighbour's.
std::vector<Eigen::Vector3d> CameraPoints() {
  return {{-0.09, 0.0, 1.5}, {-0.03, 0.0, 1.5},  {0.03, 0.0, 1.5},
          {0.09, 0.0, 1.5},  {0.02, -0.25, 1.8}, {-0.15, 0.2, 1.3}};
}

// Where the tree stands relative to the camera (any rigid transform will do).
Eigen::Isometry3d TreeFromCamera() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
               Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(1.0, 2.0, 0.5);
  return t;
}

// The true pose followed by a camera-frame error: `yaw_deg` about the camera's y axis and `shift_m`
// along its x axis.
Eigen::Isometry3d PerturbedPose(double yaw_deg, double shift_m) {
  Eigen::Isometry3d error = Eigen::Isometry3d::Identity();
  error.linear() =
      Eigen::AngleAxisd(DegToRad(yaw_deg), Eigen::Vector3d::UnitY()).toRotationMatrix();
  error.translation() = Eigen::Vector3d(shift_m, 0.0, 0.0);
  return TreeFromCamera() * error;
}

Tree TreeWithMarkers(const std::vector<Eigen::Vector3d>& camera_points) {
  Tree tree;
  for (size_t i = 0; i < camera_points.size(); ++i) {
    Marker m;
    m.id = static_cast<int>(i);
    m.parent = i == 0 ? -1 : 0;
    m.position = TreeFromCamera() * camera_points[i];
    tree.markers.push_back(m);
  }
  return tree;
}

class InitFromTreeTest : public ::testing::Test {
 protected:
  // Draws a two-frame stream of `drawn` (a marker with z <= 0 is not drawn) into pull/.
  void Draw(std::vector<Eigen::Vector3d> drawn) {
    stream_.positions = {drawn, drawn};
    pull_ = test::TempDir() / "pull";
    test::WriteDrawnStream(stream_, pull_);
  }
  Eigen::Vector2d Truth(int id) const { return stream_.intrinsics.Project(CameraPoints()[id]); }

  test::DrawnStream stream_;
  fs::path pull_;
};

TEST_F(InitFromTreeTest, AnExactPoseFindsEveryMarkerAtItsTape) {
  Draw(CameraPoints());
  const InitFromTreeResult r =
      InitFromTree(pull_, TreeWithMarkers(CameraPoints()), TreeFromCamera(), {});
  ASSERT_EQ(r.init.markers.size(), 6u);
  EXPECT_EQ(r.init.frame, 0);
  for (const MarkerPixel& m : r.init.markers) {
    EXPECT_LT((m.pixel - Truth(m.id)).norm(), 0.6) << "marker " << m.id;
  }
  EXPECT_LT(r.shift_px.norm(), 1.0);
  EXPECT_TRUE(r.warnings.empty());
}

TEST_F(InitFromTreeTest, ARegistrationErrorLargerThanTheTapeSpacingIsCorrected) {
  Draw(CameraPoints());
  const Eigen::Isometry3d pose = PerturbedPose(1.5, 0.02);
  // The test means something only if the nearest tape of some projection is a neighbour's.
  int nearest_wrong = 0;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector2d p =
        stream_.intrinsics.Project(pose.inverse() * (TreeFromCamera() * CameraPoints()[i]));
    int nearest = 0;
    for (int j = 1; j < 6; ++j) {
      if ((Truth(j) - p).norm() < (Truth(nearest) - p).norm()) nearest = j;
    }
    nearest_wrong += nearest != i;
  }
  ASSERT_GE(nearest_wrong, 3);

  const InitFromTreeResult r = InitFromTree(pull_, TreeWithMarkers(CameraPoints()), pose, {});
  ASSERT_EQ(r.init.markers.size(), 6u);
  for (const MarkerPixel& m : r.init.markers) {
    EXPECT_LT((m.pixel - Truth(m.id)).norm(), 0.6) << "marker " << m.id;
  }
  EXPECT_GT(r.shift_px.norm(), 6.0);
}

TEST_F(InitFromTreeTest, AHiddenMarkerIsReportedNotGivenANeighboursTape) {
  std::vector<Eigen::Vector3d> drawn = CameraPoints();
  drawn[2].z() = -1.0;  // not drawn: hidden in the first frame
  Draw(drawn);
  const InitFromTreeResult r =
      InitFromTree(pull_, TreeWithMarkers(CameraPoints()), PerturbedPose(1.0, 0.01), {});
  ASSERT_EQ(r.init.markers.size(), 5u);
  for (const MarkerPixel& m : r.init.markers) {
    EXPECT_NE(m.id, 2);
    EXPECT_LT((m.pixel - Truth(m.id)).norm(), 0.6) << "marker " << m.id;
  }
  EXPECT_EQ(r.markers[2].status, MarkerInitStatus::kNoBlob);
  EXPECT_FALSE(r.markers[2].pixel.has_value());
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], HasSubstr("marker 2"));
}

TEST_F(InitFromTreeTest, AskedToAHiddenMarkerStartsAtItsCorrectedProjection) {
  std::vector<Eigen::Vector3d> drawn = CameraPoints();
  drawn[2].z() = -1.0;
  Draw(drawn);
  InitFromTreeOptions options;
  options.keep_unmatched = true;
  const InitFromTreeResult r =
      InitFromTree(pull_, TreeWithMarkers(CameraPoints()), PerturbedPose(1.0, 0.01), options);
  ASSERT_EQ(r.init.markers.size(), 6u);
  EXPECT_EQ(r.markers[2].status, MarkerInitStatus::kProjected);
  // The correction the other five agree on carries the hidden one to about its true pixel.
  EXPECT_LT((*r.markers[2].pixel - Truth(2)).norm(), 1.0);
  EXPECT_GT((r.markers[2].projected - Truth(2)).norm(), 4.0);
}

TEST_F(InitFromTreeTest, APoseOffByMoreThanItsGateMatchesNothingAndSaysSo) {
  Draw(CameraPoints());
  const std::string error = test::ErrorOf(
      [&] { InitFromTree(pull_, TreeWithMarkers(CameraPoints()), PerturbedPose(12.0, 0.0), {}); });
  EXPECT_THAT(error, HasSubstr("no marker of the tree matched"));
  EXPECT_THAT(error, HasSubstr("pose"));
}

TEST_F(InitFromTreeTest, MarkersOnlyOneSideKnowsAreSetApart) {
  Draw(CameraPoints());
  Tree tree = TreeWithMarkers(CameraPoints());
  tree.markers.erase(tree.markers.begin() + 5);  // markers.json has 5, the tree not
  Marker extra;
  extra.id = 9;  // the tree has 9, markers.json not
  extra.position = TreeFromCamera() * Eigen::Vector3d(0.0, 0.1, 1.5);
  tree.markers.push_back(extra);
  const InitFromTreeResult r = InitFromTree(pull_, tree, TreeFromCamera(), {});
  EXPECT_EQ(r.init.markers.size(), 5u);
  EXPECT_EQ(r.markers.back().status, MarkerInitStatus::kNotInMarkers);
  EXPECT_EQ(r.missing, std::vector<int>{5});
}

TEST_F(InitFromTreeTest, ATreeWithoutMarkersOrBadOptionsAreRefused) {
  Draw(CameraPoints());
  EXPECT_THAT(test::ErrorOf([&] { InitFromTree(pull_, Tree{}, TreeFromCamera(), {}, "a.json"); }),
              HasSubstr("a.json: markers"));
  InitFromTreeOptions bad;
  bad.pose_rotation_deg = -1.0;
  EXPECT_THAT(test::ErrorOf([&] {
                InitFromTree(pull_, TreeWithMarkers(CameraPoints()), TreeFromCamera(), bad);
              }),
              HasSubstr("pose_rotation_deg"));
}

TEST(CameraPoseFile, ReadsBothShapesAndRefusesOthers) {
  const fs::path dir = test::TempDir();
  WritePullCamera(TreeFromCamera(), dir / "gt.json");
  EXPECT_TRUE(ReadCameraPoseJson(dir / "gt.json").isApprox(TreeFromCamera(), 1e-9));
  const std::string pose = PoseToJson(TreeFromCamera()).dump();
  test::WriteText(dir / "reg.json", R"({"format": "simtree.pull_camera", "version": 1,
    "placed": true, "frame_from_camera": )" +
                                        pose + "}");
  EXPECT_TRUE(ReadCameraPoseJson(dir / "reg.json").isApprox(TreeFromCamera(), 1e-9));

  test::WriteText(dir / "unplaced.json", R"({"format": "simtree.pull_camera", "version": 1,
    "placed": false, "status": "too few pairs", "frame_from_camera": null})");
  EXPECT_THAT(test::ErrorOf([&] { ReadCameraPoseJson(dir / "unplaced.json"); }),
              HasSubstr("placed: the pull camera was not placed"));
  test::WriteText(dir / "short.json", R"({"world_from_camera": [1, 0, 0, 0, 0, 1, 0, 0]})");
  EXPECT_THAT(test::ErrorOf([&] { ReadCameraPoseJson(dir / "short.json"); }),
              HasSubstr("world_from_camera: expected 16 numbers"));
  test::WriteText(dir / "other.json", R"({"pose": []})");
  EXPECT_THAT(test::ErrorOf([&] { ReadCameraPoseJson(dir / "other.json"); }),
              HasSubstr("expected a pull camera pose"));
}

TEST(ProjectionMatch, ACommonTurnAndShiftIsUndoneBeforeTheAssignment) {
  std::vector<Eigen::Vector2d> projections, blobs;
  for (int i = 0; i < 8; ++i) projections.emplace_back(100 + 37 * (i % 4), 80 + 45 * (i / 4));
  const Eigen::Rotation2Dd turn(DegToRad(3.0));
  for (const Eigen::Vector2d& p : projections) {
    blobs.push_back(turn * (p - Eigen::Vector2d(150, 100)) + Eigen::Vector2d(150 + 12, 100 - 7));
  }
  blobs.erase(blobs.begin() + 5);  // projection 5 has no tape
  blobs.emplace_back(400, 300);    // a tape no projection explains
  std::swap(blobs[0], blobs[3]);   // the order of blobs means nothing
  const std::vector<double> gates(projections.size(), 20.0);
  const detail::ProjectionMatch m = detail::MatchProjections(projections, gates, blobs, {});
  const std::vector<int> expected = {3, 1, 2, 0, 4, -1, 5, 6};
  EXPECT_EQ(m.blob, expected);
  EXPECT_NEAR(m.rotation_deg, 3.0, 0.1);
  EXPECT_EQ(m.agreeing, 7);
}

}  // namespace
}  // namespace simtree::tracking

namespace simtree::tracking {
namespace {

TEST(TrackCli, InitFromATreeWritesInitJsonAndTracks) {
  const fs::path dir = test::TempDir();
  test::DrawnStream s;
  s.positions = {CameraPoints(), CameraPoints(), CameraPoints()};
  test::WriteDrawnStream(s, dir / "pull");
  std::string markers;
  for (size_t i = 0; i < CameraPoints().size(); ++i) {
    const Eigen::Vector3d p = TreeFromCamera() * CameraPoints()[i];
    markers += fmt::format(R"({}{{"id": {}, "label": "m{}", "branch": 0, "arc_length": 0.1,
      "parent": {}, "position": [{}, {}, {}]}})",
                           i == 0 ? "" : ",", i, i, i == 0 ? -1 : 0, p.x(), p.y(), p.z());
  }
  test::WriteText(dir / "tree.json", R"({"format": "simtree.tree", "version": 1,
    "metadata": {"species": "", "source": "test", "units": "m"},
    "branches": [{"id": 0, "parent": -1, "parent_node": 0, "level": 0,
                  "nodes": [[0, 0, 0, 0.05], [0, 0, 2, 0.03]]}],
    "markers": [)" + markers + "]}");
  WritePullCamera(PerturbedPose(1.5, 0.02), dir / "pose.json");
  const std::string args =
      fmt::format("-q track {} --init-from {} --pull-pose {} --out {}", (dir / "pull").string(),
                  (dir / "tree.json").string(), (dir / "pose.json").string(), (dir / "t").string());
  const test::CliResult ok = test::RunCli(args);
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  const TrackInit init = ReadTrackInitJson(dir / "t" / "init.json");
  ASSERT_EQ(init.markers.size(), 6u);
  for (const MarkerPixel& m : init.markers) {
    EXPECT_LT((m.pixel - s.intrinsics.Project(CameraPoints()[m.id])).norm(), 0.6);
  }
  EXPECT_TRUE(fs::exists(dir / "t" / "trajectories.csv"));

  test::WriteText(dir / "bad_pose.json", R"({"world_from_camera": [1, 2, 3]})");
  const test::CliResult bad = test::RunCli(fmt::format(
      "-q track {} --init-from {} --pull-pose {} --out {} --init-only", (dir / "pull").string(),
      (dir / "tree.json").string(), (dir / "bad_pose.json").string(), (dir / "u").string()));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.output, HasSubstr("bad_pose.json: world_from_camera: expected 16 numbers"));
  EXPECT_FALSE(fs::exists(dir / "u" / "init.json"));
}

}  // namespace
}  // namespace simtree::tracking
