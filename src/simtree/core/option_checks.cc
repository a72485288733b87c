#include "simtree/core/option_checks.h"

#include <cmath>

#include <fmt/format.h>

namespace simtree {

void CheckOption(bool ok, std::string_view source, std::string_view field,
                 std::string_view message) {
  if (!ok) throw OptionError(std::string(field), std::string(message), std::string(source));
}

void CheckThat(bool ok, std::string_view field, std::string_view expected, double value) {
  if (!ok) {
    throw OptionError(std::string(field), fmt::format("expected {}, got {}", expected, value));
  }
}

void CheckPositive(std::string_view field, double value) {
  CheckThat(std::isfinite(value) && value > 0, field, "> 0", value);
}

void CheckNonNegative(std::string_view field, double value) {
  CheckThat(std::isfinite(value) && value >= 0, field, ">= 0", value);
}

void CheckAtLeast(std::string_view field, double value, double min) {
  CheckThat(std::isfinite(value) && value >= min, field, fmt::format(">= {:g}", min), value);
}

void CheckCountAtLeast(std::string_view field, int64_t value, int64_t min) {
  if (value < min) {
    throw OptionError(std::string(field), fmt::format("expected >= {}, got {}", min, value));
  }
}

void CheckInRange(std::string_view field, double value, double low, double high) {
  CheckThat(value >= low && value <= high, field, fmt::format("a value in [{:g}, {:g}]", low, high),
            value);
}

void CheckShare(std::string_view field, double value) { CheckInRange(field, value, 0.0, 1.0); }

void CheckOrdered(std::string_view min_field, double min, std::string_view max_field, double max) {
  CheckThat(std::isfinite(min) && std::isfinite(max) && min <= max, max_field,
            fmt::format(">= {} ({})", min_field, min), max);
}

void CheckPositiveList(std::string_view field, const std::vector<double>& values,
                       bool may_be_empty) {
  if (values.empty() && !may_be_empty) {
    throw OptionError(std::string(field), "expected at least one value");
  }
  for (size_t i = 0; i < values.size(); ++i) {
    CheckPositive(fmt::format("{}[{}]", field, i), values[i]);
  }
}

}  // namespace simtree
