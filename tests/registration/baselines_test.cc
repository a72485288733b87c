#include "simtree/registration/baselines.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"

namespace simtree::registration {
namespace {

TEST(Baselines, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(BaselineOptions{}), "");
  EXPECT_EQ(RefusedField(BaselineOptions{.spacing_m = 0}), "spacing_m");
  EXPECT_EQ(RefusedField(BaselineOptions{.ransac_confidence = 1.5}), "ransac_confidence");
  EXPECT_EQ(RefusedField(BaselineOptions{.icp_distance_factors = {6, -3}}),
            "icp_distance_factors[1]");
}

}  // namespace
}  // namespace simtree::registration
