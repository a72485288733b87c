#include "simtree/registration/detail/pairwise.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "registration_fixtures.h"

namespace simtree::registration {
namespace {

const PairOptions kDefaults;

// Views 0, 1, 4 and 5 of a ring every 36 degrees: pairs 36, 144 and 180 degrees apart.
const test::StandInViews& Views() {
  static const test::StandInViews views = test::MakeStandInViews(6, 36.0, 11);
  return views;
}

eval::PoseError ErrorOf(const Eigen::Isometry3d& target_from_source, int s, int t) {
  const auto& v = Views();
  return eval::PairPoseError(target_from_source, v.poses[s].world_from_camera,
                             v.poses[t].world_from_camera, v.tree_points);
}

eval::PoseError ErrorOf(const PairResult& r, int s, int t) {
  return ErrorOf(r.target_from_source, s, t);
}

bool Failed(const PairResult& r, PairCheck check) {
  return std::find(r.failed_checks.begin(), r.failed_checks.end(), check) != r.failed_checks.end();
}

// A turn by `angle_deg` about view `t`'s trunk cylinder axis, then a rise of `rise_m` along it
// (view t's frame): how SAC-IA misses on a tree that looks alike from another side.
Eigen::Isometry3d AboutTrunk(int t, double angle_deg, double rise_m = 0.0) {
  const TrunkCylinder& c = *Views().views[t].trunk->cylinder;
  Eigen::Isometry3d move = Eigen::Isometry3d::Identity();
  move.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180, c.axis).toRotationMatrix();
  move.translation() = c.point - move.linear() * c.point + rise_m * c.axis;
  return move;
}

TEST(Pairwise, ViewsAreReadyWithTrunkCylinderAndSkeleton) {
  for (const RegistrationView& view : Views().views) {
    ASSERT_TRUE(view.CanRegister()) << view.name << ": " << view.failure;
    ASSERT_TRUE(view.trunk && view.trunk->cylinder) << view.name;
    EXPECT_TRUE(view.ground) << view.name;
    EXPECT_GT(view.coarse.points_.size(), 100u) << view.name;
    ASSERT_TRUE(view.features);
    EXPECT_EQ(view.features->Num(), view.coarse.points_.size());
  }
}

TEST(Pairwise, RegistersNeighboursAndOppositeViewsAtTheTree) {
  const PairOptions options;
  for (const auto& [s, t] : {std::pair{1, 0}, std::pair{4, 0}, std::pair{5, 0}}) {
    const PairResult r = RegisterPair(Views().views[s], Views().views[t], options);
    const eval::PoseError e = ErrorOf(r, s, t);
    EXPECT_TRUE(r.ok()) << s << "->" << t << ": " << r.status;
    EXPECT_LT(e.rotation_deg, 2.0) << s << "->" << t;
    EXPECT_LT(e.tree_rms_m, 0.025) << s << "->" << t;
    EXPECT_FALSE(r.trunk_constraint);  // off by default (one-sided cylinder fits are biased)
    EXPECT_GT(r.match_rate, 0.05);
    EXPECT_GT(r.rmse_m, 0.0);
  }
}

TEST(Pairwise, SharedKeyRegionsSitOnTheSameTreePoint) {
  const auto& v = Views();
  const auto shared = SharedKeyRegions(v.views[3], v.views[0]);
  ASSERT_TRUE(shared);
  const Eigen::Vector3d a = v.poses[3].world_from_camera * shared->source.center;
  const Eigen::Vector3d b = v.poses[0].world_from_camera * shared->target.center;
  EXPECT_LT((a - b).norm(), 0.03);
  EXPECT_EQ(shared->source.radius_m, shared->target.radius_m);
}

TEST(Pairwise, AViewWithoutTrunkIsAFlaggedPair) {
  RegistrationView no_trunk = Views().views[1];
  no_trunk.trunk.reset();
  no_trunk.key_region.reset();
  no_trunk.failure = "no trunk: the bottom of the view holds no upright stem";
  const PairResult r = RegisterPair(no_trunk, Views().views[0], kDefaults);
  EXPECT_EQ(r.outcome, PairOutcome::kViewCannotRegister);
  EXPECT_NE(r.status.find("no trunk"), std::string::npos) << r.status;
}

TEST(Pairwise, AWrongTransformFailsTheChecks) {
  // The right transform turned about the trunk: grounds and trunks still agree. Turned 90 deg
  // the skeletons do not either; turned 40 deg 54% of this pair's skeleton stays within the 5 cm
  // inlier distance, and only the whole view's overlap (the crown's) refuses it.
  const auto& v = Views();
  const PairResult right = RegisterPair(v.views[1], v.views[0], kDefaults);
  ASSERT_TRUE(right.ok()) << right.status;
  EXPECT_GE(right.view_overlap, kDefaults.min_fitness);
  const auto shared = SharedKeyRegions(v.views[1], v.views[0]);
  const auto s = SelectCoarse(v.views[1], &shared->source);
  const auto t = SelectCoarse(v.views[0], &shared->target);
  for (double angle_deg : {90.0, 40.0, -40.0}) {
    PairResult wrong = right;
    wrong.target_from_source = AboutTrunk(0, angle_deg) * right.target_from_source;
    wrong.coarse_overlap = CoarseOverlap(s.points, t.points, wrong.target_from_source,
                                         kDefaults.sac_ia.inlier_distance_m);
    CheckPair(v.views[1], v.views[0], kDefaults, wrong);
    EXPECT_FALSE(wrong.ok()) << angle_deg << " deg: skeleton overlap " << wrong.coarse_overlap
                             << ", view overlap " << wrong.view_overlap;
    EXPECT_EQ(wrong.outcome, PairOutcome::kFailedChecks);
    EXPECT_TRUE(Failed(wrong, PairCheck::kViewOverlap)) << angle_deg << " deg: " << wrong.status;
  }
}

TEST(Pairwise, ATurnAboutTheTrunkIsFoundAgain) {
  // A coarse result turned 100 deg about the trunk (SAC-IA's miss on a key region that looks
  // alike from another side): the turn screen finds the right turn back, and without it the
  // fine stage stays wrong.
  const auto& v = Views();
  const PairResult right = RegisterPair(v.views[1], v.views[0], kDefaults);
  ASSERT_TRUE(right.ok()) << right.status;
  const Eigen::Isometry3d wrong = AboutTrunk(0, 100.0) * right.target_from_source;
  auto error = [](const Eigen::Isometry3d& t) { return ErrorOf(t, 1, 0); };
  const TurnedFineResult found = RefineWithTurns(v.views[1], v.views[0], wrong, kDefaults);
  EXPECT_TRUE(found.screened);
  EXPECT_NE(found.turned_deg, 0.0);
  EXPECT_LT(error(found.fine.icp.target_from_source).rotation_deg, 2.0);
  PairOptions no_turns = kDefaults;
  no_turns.turned_refinements = 0;
  const TurnedFineResult stuck = RefineWithTurns(v.views[1], v.views[0], wrong, no_turns);
  EXPECT_EQ(stuck.turned_deg, 0.0);
  EXPECT_GT(error(stuck.fine.icp.target_from_source).rotation_deg, 20.0);
  EXPECT_GT(found.fine.icp.fitness, stuck.fine.icp.fitness);
}

TEST(Pairwise, AResultOverlappingWellIsNotScreened) {
  // From the right pose the view overlaps well above screen_below_overlap: no turn is screened
  // (the screen's picks there are the same basin a turn step away, measured on 450 pairs); with
  // the gate open the screen runs, and finds nothing better than the right result.
  const auto& v = Views();
  const PairResult right = RegisterPair(v.views[1], v.views[0], kDefaults);
  ASSERT_TRUE(right.ok()) << right.status;
  auto error = [](const Eigen::Isometry3d& t) { return ErrorOf(t, 1, 0); };
  const TurnedFineResult gated =
      RefineWithTurns(v.views[1], v.views[0], right.target_from_source, kDefaults);
  ASSERT_GE(gated.fine.icp.fitness, kDefaults.screen_below_overlap);
  EXPECT_FALSE(gated.screened);
  EXPECT_EQ(gated.turned_deg, 0.0);
  EXPECT_LT(error(gated.fine.icp.target_from_source).rotation_deg, 2.0);
  PairOptions always = kDefaults;
  always.screen_below_overlap = 1.0;
  const TurnedFineResult screened =
      RefineWithTurns(v.views[1], v.views[0], right.target_from_source, always);
  EXPECT_TRUE(screened.screened);
  EXPECT_LT(error(screened.fine.icp.target_from_source).rotation_deg, 2.0);
  EXPECT_NEAR(error(screened.fine.icp.target_from_source).tree_rms_m,
              error(gated.fine.icp.target_from_source).tree_rms_m, 0.005);
}

TEST(Pairwise, AResultTurnedAndRaisedAlongTheTrunkIsFoundAgainWithShifts) {
  // A coarse result turned 100 deg about the trunk and 0.4 m up along it (SAC-IA aligning two
  // different forks): turns alone cannot mend the height; the screen with shifts along the trunk
  // finds the right pose back.
  const auto& v = Views();
  const PairResult right = RegisterPair(v.views[1], v.views[0], kDefaults);
  ASSERT_TRUE(right.ok()) << right.status;
  const Eigen::Isometry3d wrong = AboutTrunk(0, 100.0, 0.4) * right.target_from_source;
  auto error = [](const Eigen::Isometry3d& t) { return ErrorOf(t, 1, 0); };
  // One way only: the reverse direction (symmetric_fine) may find the way back by itself.
  PairOptions one_way = kDefaults;
  one_way.symmetric_fine = false;
  std::vector<double> shifts;
  for (int k = -5; k <= 5; ++k) shifts.push_back(0.1 * k);
  const TurnedFineResult found = RefineWithTurns(v.views[1], v.views[0], wrong, one_way, shifts);
  EXPECT_LT(error(found.fine.icp.target_from_source).rotation_deg, 2.0);
  EXPECT_LT(error(found.fine.icp.target_from_source).tree_rms_m, 0.025);
  EXPECT_NEAR(found.shifted_m, -0.4, 0.1);
  const TurnedFineResult turns_only = RefineWithTurns(v.views[1], v.views[0], wrong, one_way);
  EXPECT_GT(error(turns_only.fine.icp.target_from_source).tree_rms_m, 0.05);
  EXPECT_GT(found.fine.icp.fitness, turns_only.fine.icp.fitness);
}

TEST(Pairwise, TheSymmetricFineStageLiesHalfwayBetweenBothDirections) {
  // The 144-deg pair from the true pose: the fine stage one way, the other way, and their mean.
  const auto& v = Views();
  const int s = 4, t = 0;
  const Eigen::Isometry3d truth =
      v.poses[t].world_from_camera.inverse() * v.poses[s].world_from_camera;
  const FineResult forward = RefinePair(v.views[s], v.views[t], truth, kDefaults);
  const Eigen::Isometry3d f = forward.icp.target_from_source;
  const Eigen::Isometry3d b =
      RefinePair(v.views[t], v.views[s], f.inverse(), kDefaults).icp.target_from_source.inverse();
  const FineResult mean = AverageWithReverse(v.views[s], v.views[t], forward, kDefaults);
  const Eigen::Isometry3d m = mean.icp.target_from_source;
  auto angle = [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& c) {
    return Eigen::AngleAxisd(a.linear() * c.linear().transpose()).angle();
  };
  EXPECT_NEAR(angle(m, f), 0.5 * angle(f, b), 1e-9);
  EXPECT_NEAR(angle(m, b), 0.5 * angle(f, b), 1e-9);
  const Eigen::Vector3d centre = v.views[s].cloud->GetCenter();
  EXPECT_LT((m * centre - 0.5 * (f * centre + b * centre)).norm(), 1e-9);
  EXPECT_GT(mean.icp.fitness, 0.3);
  const eval::PoseError e = ErrorOf(m, s, t);
  EXPECT_LT(e.rotation_deg, 2.0);
  EXPECT_LT(e.tree_rms_m, 0.025);
}

TEST(Pairwise, TwoDirectionsInDifferentPlacesAreNotAveraged) {
  // The forward fine stage stuck 100 deg off about the trunk: the reverse settles elsewhere, and
  // the result is whichever overlaps more, never a pose halfway between two basins.
  const auto& v = Views();
  const int s = 1, t = 0;
  const Eigen::Isometry3d truth =
      v.poses[t].world_from_camera.inverse() * v.poses[s].world_from_camera;
  const FineResult stuck =
      RefinePair(v.views[s], v.views[t], AboutTrunk(t, 100.0) * truth, kDefaults);
  const FineResult result = AverageWithReverse(v.views[s], v.views[t], stuck, kDefaults);
  const double spacing = std::max(v.views[s].spacing_m, v.views[t].spacing_m);
  ASSERT_TRUE(std::isfinite(result.reverse_gap_m));
  EXPECT_GT(result.reverse_gap_m, kDefaults.max_reverse_disagreement_factor * spacing);
  const double last = kDefaults.icp_distance_factors.back() * spacing;
  const double stuck_overlap =
      MeasureOverlap(*v.views[s].cloud, *v.views[t].cloud, *v.views[t].cloud_tree,
                     stuck.icp.target_from_source, last)
          .share;
  EXPECT_GE(result.icp.fitness, stuck_overlap);
  // Not averaged: the forward result as it was, or one refined from the reverse.
  const eval::PoseError e = ErrorOf(result.icp.target_from_source, s, t);
  const eval::PoseError e_stuck = ErrorOf(stuck.icp.target_from_source, s, t);
  EXPECT_TRUE(e.rotation_deg < 2.0 || std::abs(e.rotation_deg - e_stuck.rotation_deg) < 1e-9)
      << e.rotation_deg << " vs stuck " << e_stuck.rotation_deg;
}

TEST(Pairwise, AResultFoundWithoutPriorsMustOverlapMore) {
  // A centre prior nothing can meet leaves the attempts with priors without a coarse result, so
  // the retry without priors finds the result kept, and its own overlap bar applies.
  const auto& v = Views();
  PairOptions options = kDefaults;
  options.max_center_offset_share = 1e-9;
  options.min_fitness_without_priors = 0.0;
  const PairResult r = RegisterPair(v.views[1], v.views[0], options);
  EXPECT_EQ(r.attempt, PairAttempt::kWithoutPriors);
  EXPECT_TRUE(r.ok()) << r.status;
  EXPECT_LT(ErrorOf(r, 1, 0).rotation_deg, 2.0);
  options.min_fitness_without_priors = 0.99;
  const PairResult strict = RegisterPair(v.views[1], v.views[0], options);
  EXPECT_EQ(strict.attempt, PairAttempt::kWithoutPriors);
  EXPECT_TRUE(Failed(strict, PairCheck::kViewOverlap));
  EXPECT_NE(strict.status.find("at least 99%"), std::string::npos) << strict.status;
}

TEST(Pairwise, OwnKeyRegionsHoldTheForkWhenOneGroundIsSeenHigh) {
  // One view fits its ground 0.5 m higher (grass, another patch of an uneven ground): the shared
  // height puts the other view's key region on the bare trunk below the fork, while each view's
  // own key region still holds its fork, and registers the pair. (Here the shared regions'
  // result is rescued by the turn screen and ICP; on some synthetic captures it is not:
  // docs/registration.md.)
  const auto& v = Views();
  RegistrationView high = v.views[1];
  high.ground->offset -= 0.5;
  auto world = [&](int view, const Eigen::Vector3d& p) {
    return Eigen::Vector3d(v.poses[view].world_from_camera * p);
  };
  const auto shared = SharedKeyRegions(high, v.views[0]);
  ASSERT_TRUE(shared);
  EXPECT_GT((world(1, shared->source.center) - world(0, shared->target.center)).norm(), 0.3);
  EXPECT_LT((world(1, high.key_region->center) - world(0, v.views[0].key_region->center)).norm(),
            0.1);
  PairOptions own = kDefaults;
  own.own_key_regions = true;
  own.retry_other_key_regions = own.retry_without_priors = false;
  const PairResult r = RegisterPair(high, v.views[0], own);
  EXPECT_TRUE(r.ok()) << r.status;
  EXPECT_TRUE(r.own_key_regions);
  const eval::PoseError e = ErrorOf(r, 1, 0);
  EXPECT_LT(e.rotation_deg, 2.0);
  EXPECT_LT(e.tree_rms_m, 0.025);
}

TEST(Pairwise, NonsenseOptionsAreRefusedNamingTheField) {
  auto refused = [](auto change) { return test::RefusedFieldAfter<PairOptions>(change); };
  EXPECT_EQ(test::RefusedField(kDefaults), "");
  EXPECT_EQ(refused([](PairOptions& o) { o.min_fitness = 1.5; }), "min_fitness");
  EXPECT_EQ(refused([](PairOptions& o) {
              o.icp_distance_factors = {6.0, -3.0};
            }),
            "icp_distance_factors[1]");
  EXPECT_EQ(refused([](PairOptions& o) { o.medial.min_matches = 0; }), "medial.min_matches");
  EXPECT_EQ(refused([](PairOptions& o) { o.turn_step_deg = 400; }), "turn_step_deg");
  EXPECT_EQ(refused([](PairOptions& o) {
              o.max_cylinder_offset_m = std::numeric_limits<double>::quiet_NaN();
            }),
            "max_cylinder_offset_m");
  PairOptions options;
  options.sac_ia.iterations = 0;
  EXPECT_THROW(RegisterPair(Views().views[1], Views().views[0], options), InputError);
}

}  // namespace
}  // namespace simtree::registration
