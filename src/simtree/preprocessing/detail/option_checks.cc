#include "simtree/preprocessing/detail/option_checks.h"

#include <cmath>

#include <fmt/format.h>

namespace simtree::preprocessing {

void CheckPositive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0)) {
    throw OptionError(field, fmt::format("expected > 0, got {}", value));
  }
}

void CheckNonNegative(const char* field, double value) {
  if (!(std::isfinite(value) && value >= 0)) {
    throw OptionError(field, fmt::format("expected >= 0, got {}", value));
  }
}

void CheckAtLeast(const char* field, double value, double min) {
  if (!(std::isfinite(value) && value >= min)) {
    throw OptionError(field, fmt::format("expected >= {}, got {}", min, value));
  }
}

void CheckShare(const char* field, double value) { CheckRange(field, value, 0.0, 1.0); }

void CheckRange(const char* field, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    throw OptionError(field, fmt::format("expected a value in [{}, {}], got {}", lo, hi, value));
  }
}

void CheckOrdered(const char* lo_field, double lo, const char* hi_field, double hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)) {
    throw OptionError(lo_field, fmt::format("expected at most {} ({}), got {}", hi_field, hi, lo));
  }
}

void CheckPositiveList(const char* field, const std::vector<double>& values, bool may_be_empty) {
  if (values.empty() && !may_be_empty) throw OptionError(field, "expected at least one value");
  for (size_t i = 0; i < values.size(); ++i) {
    if (!(std::isfinite(values[i]) && values[i] > 0)) {
      throw OptionError(fmt::format("{}[{}]", field, i),
                        fmt::format("expected > 0, got {}", values[i]));
    }
  }
}

}  // namespace simtree::preprocessing
