#pragma once
// What the Validate() of an options struct uses: each check throws OptionError, an InputError
// from "options" that names the field and what was expected,
//   options: estimation.max_modes: expected >= 1, got 0
// A struct held inside another is validated through ValidateMember, which names its fields under
// the member that holds it ("estimation.max_modes", not "max_modes").

#include <string>

#include "simtree/core/error.h"

namespace simtree::identification {

class OptionError : public InputError {
 public:
  OptionError(const std::string& field, const std::string& expected)
      : InputError("options", field, expected), expected_(expected) {}
  const std::string& expected() const { return expected_; }

 private:
  std::string expected_;
};

// Throws OptionError(field, "expected <expected>, got <value>") unless `ok`.
void RequireOption(bool ok, const std::string& field, const std::string& expected, double value);
// Finite and > 0.
void RequirePositive(double value, const std::string& field);
// Finite and >= 0.
void RequireNonNegative(double value, const std::string& field);
// A share: in [0, 1].
void RequireShare(double value, const std::string& field);
// An integer >= `min`.
void RequireAtLeast(int value, int min, const std::string& field);

// `options.Validate()`, with every field it names put under `member`.
template <typename Options>
void ValidateMember(const Options& options, const std::string& member) {
  try {
    options.Validate();
  } catch (const OptionError& e) {
    throw OptionError(member + "." + e.where(), e.expected());
  }
}

}  // namespace simtree::identification
