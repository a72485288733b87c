// Pairs that cannot pass their checks are declined after their first attempt, without the
// retries: when they overlap too little for any retry to rescue (decline_below_overlap), when
// they have spent their time (max_pair_seconds), or, in RegisterViews, when the chain of trusted
// pairs between their views agrees with their first result (chained_decline_factor).
#include <algorithm>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "registration_fixtures.h"
#include "simtree/registration/detail/pairwise.h"
#include "simtree/registration/register.h"

namespace simtree::registration {
namespace {

// A view of tree01 and one of another tree: nothing the two see is the same.
const RegistrationView& TreeOne() {
  static const RegistrationView view = test::MakeStandInViews(1, 36.0, 11).views[0];
  return view;
}
const RegistrationView& TreeTwo() {
  static const RegistrationView view =
      test::MakeStandInViews(1, 36.0, 99, {}, "tree02.txt").views[0];
  return view;
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PairDecline, APairOverlappingTooLittleForAnyRetryIsDeclinedAfterItsFirstAttempt) {
  PairOptions options;
  options.decline_below_overlap = 0.3;
  const PairResult r = RegisterPair(TreeTwo(), TreeOne(), options);
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.attempts.size(), 1u) << r.status;
  EXPECT_TRUE(r.attempts[0].refined);
  EXPECT_LT(r.view_overlap, 0.3);
  EXPECT_TRUE(Has(r.declined, "declined without retries")) << r.declined;
  EXPECT_TRUE(Has(r.status, r.declined)) << r.status;
}

TEST(PairDecline, NoRetryStartsOnceThePairHasSpentItsTime) {
  PairOptions options;
  options.decline_below_overlap = 0.0;
  options.max_pair_seconds = 1e-6;
  const PairResult r = RegisterPair(TreeTwo(), TreeOne(), options);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.attempts.size(), 1u) << r.status;
  EXPECT_TRUE(Has(r.declined, "s spent")) << r.declined;
}

TEST(PairDecline, APairTheTrustedChainExplainsIsNotRetried) {
  // Four views 36 deg apart, every pair registered; the bar on the view overlap is set between
  // what the neighbours and what the views furthest apart overlap, so the latter fail their
  // checks with a right result, which the chain of neighbours confirms.
  const test::StandInViews v = test::MakeStandInViews(4, 36.0, 11);
  MultiViewOptions options;
  options.neighbour_span = 3;
  options.closed_ring = false;
  options.pair.min_fitness = 0.55;
  options.pair.max_pair_seconds = 0.0;  // the outcome must not depend on the machine's load
  const MultiViewResult result = RegisterViews(v.views, options);
  int declined = 0;
  for (const PairEdge& edge : result.pairs) {
    const PairResult& r = edge.result;
    if (!Has(r.declined, "trusted pairs' chain")) continue;
    ++declined;
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.attempts.size(), 1u);
    const eval::PoseError e =
        eval::PairPoseError(r.target_from_source, v.poses[edge.source].world_from_camera,
                            v.poses[edge.target].world_from_camera, v.tree_points);
    EXPECT_LT(e.rotation_deg, 2.0) << edge.source << "->" << edge.target;
  }
  EXPECT_GE(declined, 1);
  EXPECT_EQ(result.RegisteredCount(), 4);
}

TEST(PairDecline, NonsenseOptionsAreRefusedNamingTheField) {
  EXPECT_EQ(
      test::RefusedFieldAfter<PairOptions>([](PairOptions& o) { o.decline_below_overlap = 1.5; }),
      "decline_below_overlap");
  EXPECT_EQ(test::RefusedFieldAfter<PairOptions>([](PairOptions& o) { o.max_pair_seconds = -1; }),
            "max_pair_seconds");
  EXPECT_EQ(test::RefusedFieldAfter<MultiViewOptions>(
                [](MultiViewOptions& o) { o.chained_decline_factor = -1; }),
            "chained_decline_factor");
}

}  // namespace
}  // namespace simtree::registration
