#include "simtree/identification/detail/branch_modes.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::identification {
namespace {

LinkModeShare Pole(double f, double strength) {
  LinkModeShare m;
  m.frequency_hz = f;
  m.damping_ratio = 0.03;
  m.amplitude = strength;
  m.plane_amplitude = {strength, 0.5 * strength};
  m.strength = strength;
  return m;
}

// Shares as ModeShares gives them: strongest first, over the strongest.
std::vector<LinkModeShare> Link(std::vector<LinkModeShare> poles) {
  std::sort(poles.begin(), poles.end(),
            [](const LinkModeShare& a, const LinkModeShare& b) { return a.strength > b.strength; });
  for (LinkModeShare& p : poles) p.share = p.strength / poles.front().strength;
  return poles;
}

std::vector<std::vector<LinkModeShare>> TrunkAndTwoBranches() {
  return {
      Link({Pole(1.1, 1.0), Pole(2.6, 0.05)}),
      Link({Pole(1.1, 1.0), Pole(2.6, 0.6)}),
      Link({Pole(1.1, 1.0), Pole(2.6, 0.04)}),
  };
}

// The trunk sways at 1.1 Hz and barely at 2.6 Hz; a branch rides on the sway (its strongest pole)
// but carries 2.6 Hz far more than the trunk: by participation that is its own mode. A second
// branch rides on the sway only and keeps it; the trunk, without a measured parent, keeps its
// strongest pole.
TEST(BranchModes, ByParticipationEachBranchTakesThePoleItCarriesMoreThanItsParent) {
  std::vector<std::vector<LinkModeShare>> links = TrunkAndTwoBranches();
  BranchModeOptions options;
  options.by_participation = true;
  const std::vector<BranchMode> modes = ChooseBranchModes(links, {-1, 0, 0}, options);
  ASSERT_EQ(modes.size(), 3u);
  EXPECT_DOUBLE_EQ(modes[0].value.frequency_hz, 1.1);
  EXPECT_TRUE(modes[0].strongest);
  EXPECT_DOUBLE_EQ(modes[1].value.frequency_hz, 2.6);
  EXPECT_FALSE(modes[1].strongest);
  EXPECT_NEAR(modes[1].participation, BranchModeOptions{}.max_participation, 1e-9);  // 12, capped
  EXPECT_DOUBLE_EQ(modes[1].planes[1].amplitude, 0.3);
  EXPECT_DOUBLE_EQ(modes[2].value.frequency_hz, 1.1);
  EXPECT_TRUE(modes[2].strongest);
  // Every pole of a link with a parent carries its participation.
  EXPECT_NEAR(links[1][0].participation, 1.0, 1e-12);
}

// By default the branch keeps the link's dominant mode; the most participating pole is reported.
TEST(BranchModes, ByDefaultTheDominantModeWithTheMostParticipatingBeside) {
  std::vector<std::vector<LinkModeShare>> links = TrunkAndTwoBranches();
  const std::vector<BranchMode> modes = ChooseBranchModes(links, {-1, 0, 0});
  EXPECT_DOUBLE_EQ(modes[1].value.frequency_hz, 1.1);
  EXPECT_TRUE(modes[1].strongest);
  EXPECT_DOUBLE_EQ(modes[1].most_participating_hz, 2.6);
  EXPECT_NE(modes[1].why.find("most participating 2.600 Hz"), std::string::npos) << modes[1].why;
  EXPECT_TRUE(std::isnan(modes[0].most_participating_hz));
}

// A pole the link itself carries weakly is noise or a neighbour's tail, however little its
// parent carries of it.
TEST(BranchModes, WeakPolesAreNoCandidates) {
  std::vector<std::vector<LinkModeShare>> links = {
      Link({Pole(1.1, 1.0)}),
      Link({Pole(1.1, 1.0), Pole(4.0, 0.1)}),
  };
  BranchModeOptions options;
  options.by_participation = true;
  const std::vector<BranchMode> modes = ChooseBranchModes(links, {-1, 0}, options);
  EXPECT_DOUBLE_EQ(modes[1].value.frequency_hz, 1.1);
  EXPECT_EQ(links[1][1].participation, BranchModeOptions{}.max_participation);
}

TEST(BranchModes, NoPoleNoMode) {
  std::vector<std::vector<LinkModeShare>> links = {{}};
  const std::vector<BranchMode> modes = ChooseBranchModes(links, {-1});
  EXPECT_EQ(modes[0].value.status, EstimateStatus::kFailed);
}

TEST(BranchModes, OptionsOutOfRangeNameTheField) {
  BranchModeOptions options;
  options.min_share = 1.5;
  EXPECT_THROW(options.Validate(), InputError);
  options = {};
  options.max_participation = 0.5;
  try {
    options.Validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_participation"), std::string::npos);
  }
}

}  // namespace
}  // namespace simtree::identification
