#pragma once
// The checks behind every reconstruction options struct's Validate(): each throws an OptionError
// (an InputError from "options" naming the field) when a value makes no sense, so a bad option
// fails before any work with a message such as
//   options: trunk.max_tilt_rad: expected within [0, 1.5708], got 2
// NaN fails every check.

#include <cstdint>
#include <string>
#include <string_view>

#include "simtree/core/error.h"

namespace simtree::reconstruction {

// A nonsense option value: `field` is its name ("trunk.slices"), `expected` what it must be and
// what it was ("expected >= 1, got 0").
class OptionError : public InputError {
 public:
  OptionError(const std::string& field, const std::string& expected)
      : InputError("options", field, expected), expected_(expected) {}
  const std::string& expected() const { return expected_; }

 private:
  std::string expected_;
};

// Finite and > 0.
void CheckPositive(std::string_view field, double value);
// Finite and >= 0.
void CheckNonNegative(std::string_view field, double value);
// Within [low, high].
void CheckWithin(std::string_view field, double value, double low, double high);
// Not NaN and >= low.
void CheckNotBelow(std::string_view field, double value, double low);
// A share: within [0, 1].
void CheckShare(std::string_view field, double value);
// An integer >= low.
void CheckAtLeast(std::string_view field, int64_t value, int64_t low);
// `max` is not below `min` (their fields named as given).
void CheckOrdered(std::string_view min_field, double min, std::string_view max_field, double max);

// Validates an options struct nested in another, naming its fields `name.field`.
template <typename Options>
void CheckNested(std::string_view name, const Options& nested) {
  try {
    nested.Validate();
  } catch (const OptionError& e) {
    throw OptionError(std::string(name) + "." + e.where(), e.expected());
  }
}

}  // namespace simtree::reconstruction
