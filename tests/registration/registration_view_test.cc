#include "simtree/registration/registration_view.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::registration {
namespace {

TEST(RegistrationView, NonsenseOptionsAreRefusedNamingTheField) {
  using Options = RegistrationViewOptions;
  auto refused = [](auto change) { return test::RefusedFieldAfter<Options>(change); };
  EXPECT_EQ(test::RefusedField(Options{}), "");
  EXPECT_EQ(refused([](Options& o) { o.feature_radius_factor = 0; }), "feature_radius_factor");
  EXPECT_EQ(refused([](Options& o) { o.projection.neighbourhood_m = -1; }),
            "projection.neighbourhood_m");
  EXPECT_EQ(refused([](Options& o) { o.skeleton.rounds = 0; }), "skeleton.rounds");
  EXPECT_EQ(refused([](Options& o) { o.key_region.height_share = 2; }), "key_region.height_share");
  Options options;
  options.trunk.slice_height_m = 0;
  EXPECT_THROW(PrepareView("view_00", preprocessing::PreprocessResult{}, options), InputError);
}

TEST(RegistrationView, AViewThatFailedInPreprocessingKeepsItsFailure) {
  std::vector<preprocessing::PreprocessedView> preprocessed(2);
  preprocessed[0].name = "view_00";
  preprocessed[0].failure = "every pixel is 0";
  preprocessed[1].name = "view_01";
  preprocessed[1].result.emplace();  // no points
  const std::vector<RegistrationView> views = PrepareViews(preprocessed);
  ASSERT_EQ(views.size(), 2u);
  EXPECT_EQ(views[0].name, "view_00");
  EXPECT_EQ(views[0].failure, "every pixel is 0");
  EXPECT_FALSE(views[1].CanRegister());
  EXPECT_EQ(views[1].failure, "only 0 tree points");
}

}  // namespace
}  // namespace simtree::registration
