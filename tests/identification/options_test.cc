#include "simtree/core/option_checks.h"

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/identification/detail/test_signals.h"
#include "simtree/identification/identify.h"
#include "simtree/identification/spectrum_plot.h"

namespace simtree::identification {
namespace {

using ::testing::HasSubstr;

// One bad value per field family: each must throw an InputError from "options" that names the
// field (under the member that holds it) and what was expected.
struct BadValue {
  std::string field;
  std::function<void()> validate;
};

template <typename Options>
BadValue Bad(const std::string& field, std::function<void(Options&)> edit) {
  return {field, [edit] {
            Options options;
            edit(options);
            options.Validate();
          }};
}

void ExpectNamed(const std::vector<BadValue>& cases) {
  for (const BadValue& c : cases) {
    try {
      c.validate();
      ADD_FAILURE() << c.field << ": no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "options") << c.field;
      EXPECT_EQ(e.where(), c.field) << e.what();
      EXPECT_THAT(e.what(), HasSubstr("expected")) << c.field;
    }
  }
}

TEST(Options, DefaultsAreValid) {
  EXPECT_NO_THROW(IdentifyOptions{}.Validate());
  EXPECT_NO_THROW(RangeOptions{}.Validate());
  EXPECT_NO_THROW(SpectrumPlotOptions{}.Validate());
  EXPECT_NO_THROW(SpectrumOptions{}.Validate());
  EXPECT_NO_THROW(DecayRecordOptions{}.Validate());
}

TEST(Options, IdentifyNamesTheNestedField) {
  ExpectNamed({
      Bad<IdentifyOptions>("window_s", [](auto& o) { o.window_s = -1; }),
      Bad<IdentifyOptions>(
          "release_time_s",
          [](auto& o) { o.release_time_s = std::numeric_limits<double>::quiet_NaN(); }),
      Bad<IdentifyOptions>("estimation.max_modes", [](auto& o) { o.estimation.max_modes = 0; }),
      Bad<IdentifyOptions>("estimation.max_gap_fraction",
                           [](auto& o) { o.estimation.max_gap_fraction = 1.5; }),
      Bad<IdentifyOptions>("estimation.max_frequency_hz",
                           [](auto& o) {
                             o.estimation.min_frequency_hz = 2;
                             o.estimation.max_frequency_hz = 1;
                           }),
      Bad<IdentifyOptions>("estimation.max_damping_ratio",
                           [](auto& o) { o.estimation.max_damping_ratio = 1; }),
      Bad<IdentifyOptions>("estimation.zero_pad_factor",
                           [](auto& o) { o.estimation.zero_pad_factor = 0; }),
      Bad<IdentifyOptions>("release.quiet_fraction",
                           [](auto& o) { o.release.quiet_fraction = 0.6; }),
      Bad<IdentifyOptions>(
          "release.min_hold_s",
          [](auto& o) { o.release.min_hold_s = std::numeric_limits<double>::quiet_NaN(); }),
      Bad<IdentifyOptions>("deflection.rest_fraction",
                           [](auto& o) { o.deflection.rest_fraction = 0; }),
      Bad<IdentifyOptions>("deflection.camera_up",
                           [](auto& o) { o.deflection.camera_up.setZero(); }),
      Bad<IdentifyOptions>("outliers.half_window", [](auto& o) { o.outliers.half_window = 2; }),
      Bad<IdentifyOptions>("outliers.max_trimmed", [](auto& o) { o.outliers.max_trimmed = 3; }),
      Bad<IdentifyOptions>("outliers.threshold", [](auto& o) { o.outliers.threshold = -6; }),
      Bad<IdentifyOptions>("joint.components", [](auto& o) { o.joint.components = 0; }),
      Bad<IdentifyOptions>("joint.min_split", [](auto& o) { o.joint.min_split = -0.1; }),
      Bad<IdentifyOptions>("branch_modes.min_share", [](auto& o) { o.branch_modes.min_share = 2; }),
  });
}

TEST(Options, OtherStructsNameTheirField) {
  ExpectNamed({
      Bad<RangeOptions>("max_damping_relative_std",
                        [](auto& o) { o.max_damping_relative_std = 0; }),
      Bad<SpectrumPlotOptions>("width", [](auto& o) { o.width = 10; }),
      Bad<SpectrumPlotOptions>("max_frequency_hz", [](auto& o) { o.max_frequency_hz = -1; }),
      Bad<SpectrumOptions>("exponential_rate", [](auto& o) { o.exponential_rate = -1; }),
      Bad<DecayRecordOptions>("fps", [](auto& o) { o.fps = 0; }),
      Bad<DecayRecordOptions>("gap_rate", [](auto& o) { o.gap_rate = 2; }),
  });
}

TEST(Options, TheEntryFunctionValidatesBeforeAnyWork) {
  IdentifyOptions options;
  options.estimation.max_iterations = -3;
  EXPECT_THAT([&] { IdentifyMaterials(Trajectories{}, {}, options); },
              ::testing::ThrowsMessage<InputError>(
                  HasSubstr("options: estimation.max_iterations: expected >= 1, got -3")));
}

}  // namespace
}  // namespace simtree::identification
