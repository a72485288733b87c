#include "simtree/identification/identify.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/identification/detail/test_signals.h"
#include "simtree/tracking/tracker_error.h"

namespace simtree::identification {
namespace {

using ::testing::HasSubstr;

// Three links, each with its own dominant mode, a weaker shared mode and tracker noise.
SyntheticMarkerTree ThreeLinks() {
  SyntheticMarkerTree tree;
  tree.root_motion[0] = {{0.9, 0.025, 0.02, 0.0}};
  tree.root_motion[2] = {{0.9, 0.025, 0.01, 0.0}};
  tree.links.resize(3);
  tree.links[0].rest_direction = {0.3, -1.0, 0.0};
  tree.links[0].length_m = 0.7;
  tree.links[0].theta_u = {{1.05, 0.031, 0.10, 0.0}, {2.4, 0.05, 0.02, 0.0}};
  tree.links[0].theta_w = {{1.05, 0.031, 0.04, 0.0}};
  tree.links[1].parent = 0;
  tree.links[1].rest_direction = {1.0, -0.6, 0.2};
  tree.links[1].length_m = 0.5;
  tree.links[1].theta_u = {{1.32, 0.045, 0.12, 0.0}};
  tree.links[1].theta_w = {{1.05, 0.031, 0.03, 0.0}};
  tree.links[2].parent = 0;
  tree.links[2].rest_direction = {-1.0, -0.4, 0.3};
  tree.links[2].length_m = 0.5;
  tree.links[2].theta_u = {{1.48, 0.058, 0.09, 0.0}};
  tree.links[2].theta_w = {{1.48, 0.058, 0.05, 0.0}};
  return tree;
}

struct Truth {
  double f, zeta;
};
const Truth kTruth[4] = {{0.9, 0.025}, {1.05, 0.031}, {1.32, 0.045}, {1.48, 0.058}};

TEST(Identify, EveryLinkWithinOnePercentInFrequencyAndFifteenInDampingUnderTrackerNoise) {
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(ThreeLinks(), 30.0, 2.0, 10.0, &markers);
  tracking::TrackerErrorOptions noise;
  noise.seed = 4;
  const IdentificationResult r =
      IdentifyMaterials(tracking::SimulateTrackerError(truth, noise), markers);
  EXPECT_EQ(r.release.outcome, ReleaseOutcome::kDetected) << r.release.note;
  EXPECT_NEAR(r.window_start_s, 2.0, 0.15);
  ASSERT_EQ(r.links.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const LinkIdentification& link = r.links[k];
    ASSERT_TRUE(link.measured()) << link.deflection.link.label << ": " << link.value.message;
    EXPECT_NEAR(link.value.frequency_hz, kTruth[k].f, 0.01 * kTruth[k].f) << k;
    EXPECT_NEAR(link.value.damping_ratio, kTruth[k].zeta, 0.15 * kTruth[k].zeta) << k;
    EXPECT_GT(link.value.frequency_std_hz, 0) << k;
    ASSERT_EQ(link.estimates.size(), 3u);
    EXPECT_EQ(link.estimates.front().estimator, kDefaultEstimator);
    EXPECT_NE(link.Find(EstimatorKind::kHalfPowerFft), nullptr);
  }
  const MaterialRanges ranges = r.Ranges();
  EXPECT_EQ(ranges.measured, 4);
  EXPECT_NEAR(ranges.min_frequency_hz, 0.9, 0.01);
  EXPECT_NEAR(ranges.max_frequency_hz, 1.48, 0.015);
  EXPECT_THAT(FormatRanges(ranges, "test"), HasSubstr("(4 of 4 links measured)"));
  EXPECT_THAT(FormatLinkTable(r), HasSubstr("M0-M1"));
}

// A value the fit could not pin down does not set a range's end: it is listed as uncertain and
// only the range over every value still shows it.
// The links' modes are the tree's: with joint poles each link still reads its own dominant one.
TEST(Identify, JointPolesKeepEachLinksOwnDominantMode) {
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(ThreeLinks(), 30.0, 2.0, 10.0, &markers);
  tracking::TrackerErrorOptions noise;
  noise.seed = 4;
  IdentifyOptions options;
  options.joint_poles = true;
  options.choose_per_link = false;  // every link on the joint poles (--joint-poles)
  const IdentificationResult r =
      IdentifyMaterials(tracking::SimulateTrackerError(truth, noise), markers, options);
  EXPECT_EQ(r.joint_poles, JointPolesOutcome::kApplied) << r.joint_poles_note;
  ASSERT_EQ(r.links.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const LinkIdentification& link = r.links[k];
    ASSERT_TRUE(link.measured()) << link.deflection.link.label << ": " << link.value.message;
    EXPECT_TRUE(link.estimates.front().joint_poles) << k;
    EXPECT_NEAR(link.value.frequency_hz, kTruth[k].f, 0.01 * kTruth[k].f) << k;
    EXPECT_NEAR(link.value.damping_ratio, kTruth[k].zeta, 0.15 * kTruth[k].zeta) << k;
    EXPECT_GT(link.value.damping_std, 0) << k;
  }
}

// A link's reading on the shared poles reports at least what its own fit's disagreement with it
// says beyond the own fit's deviation (shared_pole_uncertainty.h), whichever reading is used.
TEST(Identify, SharedReadingsCarryTheirDisagreementWithTheOwnFit) {
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(ThreeLinks(), 30.0, 2.0, 10.0, &markers);
  tracking::TrackerErrorOptions noise;
  noise.seed = 4;
  const IdentificationResult r =
      IdentifyMaterials(tracking::SimulateTrackerError(truth, noise), markers);
  ASSERT_EQ(r.joint_poles, JointPolesOutcome::kApplied) << r.joint_poles_note;
  int widened = 0;
  for (const LinkIdentification& link : r.links) {
    const ModalEstimate &own = link.poles.own, &joint = link.poles.joint;
    if (own.status != EstimateStatus::kOk || joint.status != EstimateStatus::kOk) continue;
    const double df = joint.frequency_hz - own.frequency_hz;
    const double dz = joint.damping_ratio - own.damping_ratio;
    const double f_excess = df * df - own.frequency_std_hz * own.frequency_std_hz;
    const double z_excess = dz * dz - own.damping_std * own.damping_std;
    const std::string& label = link.deflection.link.label;
    EXPECT_GE(joint.frequency_std_hz, std::sqrt(std::max(0.0, f_excess)) * (1 - 1e-9)) << label;
    EXPECT_GE(joint.damping_std, std::sqrt(std::max(0.0, z_excess)) * (1 - 1e-9)) << label;
    widened += f_excess > 0 || z_excess > 0;
    if (link.poles.shared) {
      EXPECT_EQ(link.value.frequency_std_hz, joint.frequency_std_hz);
    }
  }
  // Links 1-3 ring at their own frequencies: the shared poles miss at least one of them.
  EXPECT_GE(widened, 1);
}

TEST(Identify, RangesLeaveOutValuesWithALargeUncertainty) {
  auto value = [](double f, double f_std, double zeta, double zeta_std) {
    ModalEstimate e;
    e.frequency_hz = f;
    e.frequency_std_hz = f_std;
    e.damping_ratio = zeta;
    e.damping_std = zeta_std;
    return e;
  };
  ModalEstimate missing;
  missing.status = EstimateStatus::kFlat;
  const std::vector<LabeledEstimate> links = {
      {"a", value(1.0, 0.001, 0.030, 0.001)},
      {"b", value(1.2, 0.002, 0.040, 0.002)},
      {"c", value(1.1, 0.001, 0.170, 0.080)},  // damping known to 47%: uncertain
      {"d", value(2.5, 0.200, 0.035, 0.002)},  // frequency known to 8%: uncertain
      {"e", value(1.3, ModalEstimate::kNaN, 0.050, ModalEstimate::kNaN)},      // none given: counts
      {"g", value(2.9, std::numeric_limits<double>::infinity(), 0.030, 0.0)},  // broken: uncertain
      {"f", missing}};
  const MaterialRanges r = ComputeRanges(links);
  EXPECT_EQ(r.links, 7);
  EXPECT_EQ(r.measured, 6);
  EXPECT_EQ(r.frequency_count, 4);
  EXPECT_EQ(r.damping_count, 5);  // g's damping has a (zero) standard deviation: counts
  EXPECT_DOUBLE_EQ(r.min_frequency_hz, 1.0);
  EXPECT_DOUBLE_EQ(r.max_frequency_hz, 1.3);  // d's 2.5 Hz left out, c's frequency kept
  EXPECT_DOUBLE_EQ(r.min_damping, 0.030);
  EXPECT_DOUBLE_EQ(r.max_damping, 0.050);  // c's 0.17 left out, d's damping kept
  EXPECT_DOUBLE_EQ(r.all_max_damping, 0.170);
  EXPECT_DOUBLE_EQ(r.all_max_frequency_hz, 2.9);
  EXPECT_EQ(r.uncertain, (std::vector<std::string>{"c", "d", "g"}));
  EXPECT_THAT(FormatRanges(r, "test"), HasSubstr("3 uncertain, left out: c, d, g"));

  // Tighter bounds leave out more; none measured gives NaN ranges.
  const MaterialRanges tight = ComputeRanges(
      links, {.max_frequency_relative_std = 0.0015, .max_damping_relative_std = 0.04});
  EXPECT_EQ(tight.frequency_count, 3);  // a, c and e (no uncertainty)
  EXPECT_EQ(tight.damping_count, 3);    // a, e and g
  const MaterialRanges none = ComputeRanges({{"f", missing}});
  EXPECT_EQ(none.measured, 0);
  EXPECT_TRUE(std::isnan(none.min_frequency_hz));
  EXPECT_TRUE(none.uncertain.empty());
}

TEST(Identify, AGivenReleaseTimeAndWindowAreUsed) {
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(ThreeLinks(), 30.0, 2.0, 10.0, &markers);
  IdentifyOptions options;
  options.release_time_s = 2.0;
  options.window_s = 6.0;
  options.compare_estimators = false;
  // Per-link fits: on these noise-free records the joint fit keeps adding poles to its limit,
  // minutes under the sanitizers, and the window is what this test is about.
  options.joint_poles = false;
  const IdentificationResult r = IdentifyMaterials(t, markers, options);
  EXPECT_NEAR(r.window_start_s, 2.0, 1e-9);
  EXPECT_NEAR(r.window_end_s, 8.0 - 1.0 / 30, 1e-6);
  EXPECT_EQ(r.links[1].estimates.size(), 1u);
  EXPECT_NEAR(r.links[1].value.frequency_hz, 1.05, 1e-3);
  options.release_time_s = 99.0;
  EXPECT_THROW(IdentifyMaterials(t, markers, options), InputError);
}

TEST(Identify, MissingMarkersAreReportedPerLinkAndNothingTrackedIsAnError) {
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(ThreeLinks(), 30.0, 0.0, 6.0, &markers);
  markers.push_back({7, "M7", 1, std::nullopt});
  IdentifyOptions per_link;  // noise-free records: see AGivenReleaseTimeAndWindowAreUsed
  per_link.joint_poles = false;
  const IdentificationResult r = IdentifyMaterials(t, markers, per_link);
  ASSERT_EQ(r.links.size(), 5u);
  EXPECT_EQ(r.links[4].value.status, EstimateStatus::kMissingMarker);
  EXPECT_FALSE(r.links[4].value.has_frequency());
  EXPECT_THAT(r.links[4].value.message, HasSubstr("marker 7 has no trajectory"));
  EXPECT_EQ(r.Ranges().measured, 4);

  const std::vector<MarkerLink> others = {{20, "A", -1, std::nullopt}, {21, "B", 20, std::nullopt}};
  try {
    IdentifyMaterials(t, others, {}, "tracks.csv");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tracks.csv"));
    EXPECT_THAT(e.what(), HasSubstr("none of the 2 markers"));
    EXPECT_THAT(e.what(), HasSubstr("markers 0, 1, 2, 3"));
  }
}

TEST(Identify, AStillLinkIsFlatNotInvented) {
  SyntheticMarkerTree tree = ThreeLinks();
  tree.links[2].theta_u.clear();
  tree.links[2].theta_w.clear();
  std::vector<MarkerLink> markers;
  tracking::TrackerErrorOptions noise;
  const IdentificationResult r =
      IdentifyMaterials(tracking::SimulateTrackerError(
                            MakeMarkerTrajectories(tree, 30.0, 1.0, 10.0, &markers), noise),
                        markers);
  // Marker 3 hangs from marker 1, whose link swings; with that swing removed only noise is left.
  EXPECT_EQ(r.links[3].value.status, EstimateStatus::kFlat) << r.links[3].value.message;
  EXPECT_FALSE(r.links[3].value.has_damping());
}

}  // namespace
}  // namespace simtree::identification
