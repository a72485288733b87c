#pragma once
// The checks an options struct's Validate() runs. Each throws OptionError, an InputError from
// source "options" that names the field and what was expected:
//   "options: pair.sac_ia.iterations: expected > 0, got -3".
// A struct nested in another is checked through CheckNested, which puts the member's name in
// front of the field its own Validate() names.

#include <string>
#include <vector>

#include "simtree/core/error.h"

namespace simtree::preprocessing {

class OptionError : public InputError {
 public:
  OptionError(const std::string& field, const std::string& expected)
      : InputError("options", field, expected), field_(field), expected_(expected) {}
  const std::string& field() const { return field_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string field_;
  std::string expected_;
};

// Finite and > 0.
void CheckPositive(const char* field, double value);
// Finite and >= 0.
void CheckNonNegative(const char* field, double value);
// Finite and >= min.
void CheckAtLeast(const char* field, double value, double min);
// In [0, 1].
void CheckShare(const char* field, double value);
// In [lo, hi].
void CheckRange(const char* field, double value, double lo, double hi);
// lo <= hi, both finite (min and max of one quantity).
void CheckOrdered(const char* lo_field, double lo, const char* hi_field, double hi);
// Every element finite and > 0; at least one unless `may_be_empty`.
void CheckPositiveList(const char* field, const std::vector<double>& values, bool may_be_empty);

// Runs `validate` (a nested struct's Validate()) and names its fields as members of `member`.
template <class Validate>
void CheckNested(const char* member, Validate&& validate) {
  try {
    validate();
  } catch (const OptionError& e) {
    throw OptionError(std::string(member) + "." + e.field(), e.expected());
  }
}

}  // namespace simtree::preprocessing
