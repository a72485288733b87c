#pragma once
// One check's outcome from its value and limits, with the message for each outcome.

#include <string>

#include "simtree/capture_check/capture_check.h"

namespace simtree::capture_check::detail {

// Where a value passes: above its limits (a share of depth) or below them (dropped frames).
enum class Better { kHigher, kLower };

struct Limits {
  Better better = Better::kHigher;
  double warn = 0;  // worse than this: warn
  double fail = 0;  // worse than this: fail (equal to warn: never fails)
};

// The check with status from `value` against `limits`; `found` says what was measured, `fix` what
// to do (added unless ok). `scale` converts value to its displayed unit (100 for "%").
Check Grade(const std::string& name, const std::string& subject, double value,
            const std::string& unit, const Limits& limits, const std::string& found,
            const std::string& fix, double scale = 1);

// A check that failed outright (no value) or was skipped.
Check Failed(const std::string& name, const std::string& subject, const std::string& message);
Check Skipped(const std::string& name, const std::string& subject, const std::string& why);

}  // namespace simtree::capture_check::detail
