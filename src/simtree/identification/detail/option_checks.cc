#include "simtree/identification/detail/option_checks.h"

#include <cmath>

#include <fmt/format.h>

namespace simtree::identification {

void RequireOption(bool ok, const std::string& field, const std::string& expected, double value) {
  if (!ok) throw OptionError(field, fmt::format("expected {}, got {}", expected, value));
}

void RequirePositive(double value, const std::string& field) {
  RequireOption(std::isfinite(value) && value > 0, field, "> 0", value);
}

void RequireNonNegative(double value, const std::string& field) {
  RequireOption(std::isfinite(value) && value >= 0, field, ">= 0", value);
}

void RequireShare(double value, const std::string& field) {
  RequireOption(value >= 0 && value <= 1, field, "a share in [0, 1]", value);
}

void RequireAtLeast(int value, int min, const std::string& field) {
  RequireOption(value >= min, field, fmt::format(">= {}", min), value);
}

}  // namespace simtree::identification
