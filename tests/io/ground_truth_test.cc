#include "simtree/io/ground_truth.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

using test::ErrorOf;

Eigen::Isometry3d SomePose() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(2.5, -1.0, 1.2);
  return pose;
}

TEST(GroundTruth, PosesRoundTrip) {
  const auto dir = test::TempDir();
  WriteScanPoses({{"view_00", SomePose()}, {"view_01", Eigen::Isometry3d::Identity()}},
                 dir / "scan_poses.json");
  const auto poses = ReadScanPoses(dir / "scan_poses.json");
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].name, "view_00");
  EXPECT_TRUE(poses[0].world_from_camera.isApprox(SomePose(), 1e-12));
  WritePullCamera(SomePose(), dir / "pull_camera.json");
  EXPECT_TRUE(ReadPullCamera(dir / "pull_camera.json").isApprox(SomePose(), 1e-12));
}

TEST(GroundTruth, BadPosesAreClearErrors) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "p.json", R"({"world_from_camera": [1, 0, 0, 0, 0, 1, 0, 0]})");
  EXPECT_THAT(ErrorOf([&] { ReadPullCamera(dir / "p.json"); }),
              HasSubstr("world_from_camera: expected 16 numbers (a row-major 4x4 matrix), got 8"));
  test::WriteText(dir / "p.json",
                  R"({"world_from_camera": [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]})");
  EXPECT_THAT(ErrorOf([&] { ReadPullCamera(dir / "p.json"); }), HasSubstr("expected a rotation"));
  test::WriteText(dir / "p.json",
                  R"({"world_from_camera": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1]})");
  EXPECT_THAT(ErrorOf([&] { ReadPullCamera(dir / "p.json"); }),
              HasSubstr("expected the last row 0 0 0 1"));
}

TEST(GroundTruth, PullLoadRampsHoldsAndReleases) {
  PullLoad load;
  load.force_n = 40.0;
  load.ramp_start_s = 1.0;
  load.hold_start_s = 3.0;
  load.release_s = 5.0;
  EXPECT_EQ(load.ForceAt(0.5), 0.0);
  EXPECT_NEAR(load.ForceAt(2.0), 20.0, 1e-9);
  EXPECT_EQ(load.ForceAt(4.0), 40.0);
  EXPECT_EQ(load.ForceAt(4.999), 40.0);
  EXPECT_EQ(load.ForceAt(5.0), 0.0);
  const auto dir = test::TempDir();
  load.branch = 3;
  load.anchor = {1, 2, 0};
  WritePullLoad(load, dir / "pull_load.json");
  const PullLoad back = ReadPullLoad(dir / "pull_load.json");
  EXPECT_EQ(back.branch, 3);
  EXPECT_EQ(back.anchor, load.anchor);
  EXPECT_EQ(back.release_s, 5.0);
}

TEST(GroundTruth, Markers2dAndModalTruthRoundTrip) {
  const auto dir = test::TempDir();
  std::vector<MarkerFrame2d> frames(2);
  frames[1].frame = 1;
  frames[1].time_s = 1.0 / 30;
  frames[1].markers = {{0, true, 0.8, 40, {10.5, 20.25, 8, 12}}, {1, false, 0.0, 0, {0, 0, 0, 0}}};
  WriteMarkers2d(frames, dir / "markers_2d.json");
  const auto back = ReadMarkers2d(dir / "markers_2d.json");
  ASSERT_EQ(back.size(), 2u);
  ASSERT_EQ(back[1].markers.size(), 2u);
  EXPECT_TRUE(back[1].markers[0].visible);
  EXPECT_EQ(back[1].markers[0].box[1], 20.25);
  EXPECT_EQ(back[1].markers[0].visible_pixels, 40);
  EXPECT_FALSE(back[1].markers[1].visible);

  ModalTruth truth;
  truth.source = "fem";
  truth.modes = {{0.9, 0.03}, {1.3, 0.04}};
  truth.links = {{0, 1, 1.3, 0.04}};
  truth.branches = {{0, 0.9, 0.03}, {5, 1.3, 0.04}};
  WriteModalTruth(truth, dir / "modal.json");
  const ModalTruth read = ReadModalTruth(dir / "modal.json");
  EXPECT_EQ(read.source, "fem");
  ASSERT_EQ(read.links.size(), 1u);
  EXPECT_EQ(read.links[0].child, 1);
  EXPECT_EQ(read.branches[1].frequency_hz, 1.3);
  EXPECT_TRUE(read.links[0].peaks.empty());

  // The optional strongest modes of a signal round-trip too.
  truth.links[0].peaks = {{1, 1.3, 0.04, 0.02, 0.35}, {0, 0.9, 0.03, 0.004, 0.1}};
  truth.branches[1].peaks = {{1, 1.3, 0.04, 0.01, 0.2}};
  WriteModalTruth(truth, dir / "modal.json");
  const ModalTruth with_peaks = ReadModalTruth(dir / "modal.json");
  ASSERT_EQ(with_peaks.links[0].peaks.size(), 2u);
  EXPECT_EQ(with_peaks.links[0].peaks[1].mode, 0);
  EXPECT_EQ(with_peaks.links[0].peaks[0].strength, 0.35);
  EXPECT_EQ(with_peaks.links[0].peaks[1].amplitude, 0.004);
  ASSERT_EQ(with_peaks.branches[1].peaks.size(), 1u);
  EXPECT_EQ(with_peaks.branches[1].peaks[0].damping_ratio, 0.04);
  EXPECT_TRUE(with_peaks.branches[0].peaks.empty());
  // Files without the effective masses (older ones) read as absent.
  EXPECT_FALSE(with_peaks.modes[0].horizontal_mass_fraction.has_value());
  EXPECT_FALSE(with_peaks.lowest_sway_mode.has_value());

  // The optional effective-mass fractions and the lowest sway mode round-trip too.
  truth.modes[0].horizontal_mass_fraction = 0.002;
  truth.modes[0].torsion_mass_fraction = 0.7;
  truth.modes[1].horizontal_mass_fraction = 0.55;
  truth.modes[1].torsion_mass_fraction = 0.01;
  truth.lowest_sway_mode = 1;
  WriteModalTruth(truth, dir / "modal.json");
  const ModalTruth with_masses = ReadModalTruth(dir / "modal.json");
  EXPECT_EQ(with_masses.modes[0].torsion_mass_fraction, 0.7);
  EXPECT_EQ(with_masses.modes[1].horizontal_mass_fraction, 0.55);
  EXPECT_EQ(with_masses.lowest_sway_mode, 1);
  truth.lowest_sway_mode = 2;  // no such mode
  WriteModalTruth(truth, dir / "modal.json");
  EXPECT_THAT(ErrorOf([&] { ReadModalTruth(dir / "modal.json"); }), HasSubstr("lowest_sway_mode"));
  EXPECT_THAT(ErrorOf([&] { ReadModalTruth(dir / "none.json"); }), HasSubstr("missing"));
}

}  // namespace
}  // namespace simtree
