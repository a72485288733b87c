#pragma once
// The checks behind every options struct's Validate(). Each throws an OptionError, an InputError
// whose source is the options ("options" unless named) and whose `where` is the field, with what
// was expected and what was given, so a bad option fails before any work:
//   options: trunk.max_tilt_rad: expected a value in [0, 1.5708], got 2
// NaN fails every check. A struct held inside another is checked through CheckNested, which puts
// the member's name in front of the fields its own Validate() names ("trunk.max_tilt_rad").

#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "simtree/core/error.h"

namespace simtree {

// A nonsense option value: `field` its name ("trunk.slices"), `expected` what it must be and what
// it was ("expected >= 1, got 0"), `source` what holds it ("options", "simulation options").
class OptionError : public InputError {
 public:
  OptionError(const std::string& field, const std::string& expected,
              const std::string& source = "options")
      : InputError(source, field, expected), expected_(expected) {}
  const std::string& field() const { return where(); }
  const std::string& expected() const { return expected_; }

 private:
  std::string expected_;
};

// Throws OptionError(field, message, source) unless `ok`; `message` says what was expected and
// what was given.
void CheckOption(bool ok, std::string_view source, std::string_view field,
                 std::string_view message);
// Throws OptionError(field, "expected <expected>, got <value>") unless `ok`.
void CheckThat(bool ok, std::string_view field, std::string_view expected, double value);
// Finite and > 0.
void CheckPositive(std::string_view field, double value);
// Finite and >= 0.
void CheckNonNegative(std::string_view field, double value);
// Finite and >= min.
void CheckAtLeast(std::string_view field, double value, double min);
// An integer >= min.
void CheckCountAtLeast(std::string_view field, int64_t value, int64_t min);
// Any integer type: CheckCountAtLeast.
template <std::integral Value, std::integral Min>
void CheckAtLeast(std::string_view field, Value value, Min min) {
  CheckCountAtLeast(field, static_cast<int64_t>(value), static_cast<int64_t>(min));
}
// In [low, high].
void CheckInRange(std::string_view field, double value, double low, double high);
// A share: in [0, 1].
void CheckShare(std::string_view field, double value);
// min <= max, both finite (the two ends of one quantity); the error names `max_field`.
void CheckOrdered(std::string_view min_field, double min, std::string_view max_field, double max);
// Every element finite and > 0 (the error names the element, "factors[2]"); at least one unless
// `may_be_empty`.
void CheckPositiveList(std::string_view field, const std::vector<double>& values,
                       bool may_be_empty);

// Checks `nested`, an options struct (its Validate()) or a function that runs checks, and names
// the fields it refuses as members of `member` ("trunk" + "slices" = "trunk.slices").
template <typename Nested>
void CheckNested(std::string_view member, const Nested& nested) {
  try {
    if constexpr (std::invocable<const Nested&>) {
      nested();
    } else {
      nested.Validate();
    }
  } catch (const OptionError& e) {
    throw OptionError(std::string(member) + "." + e.field(), e.expected(), e.source());
  }
}

}  // namespace simtree
