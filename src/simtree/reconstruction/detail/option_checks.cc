#include "simtree/reconstruction/detail/option_checks.h"

#include <cmath>

#include <fmt/format.h>

namespace simtree::reconstruction {

void CheckPositive(std::string_view field, double value) {
  if (!(value > 0) || !std::isfinite(value)) {
    throw OptionError(std::string(field), fmt::format("expected > 0, got {}", value));
  }
}

void CheckNonNegative(std::string_view field, double value) {
  if (!(value >= 0) || !std::isfinite(value)) {
    throw OptionError(std::string(field), fmt::format("expected >= 0, got {}", value));
  }
}

void CheckWithin(std::string_view field, double value, double low, double high) {
  if (!(value >= low && value <= high)) {
    throw OptionError(std::string(field),
                      fmt::format("expected within [{:g}, {:g}], got {}", low, high, value));
  }
}

void CheckNotBelow(std::string_view field, double value, double low) {
  if (!(value >= low)) {
    throw OptionError(std::string(field), fmt::format("expected >= {:g}, got {}", low, value));
  }
}

void CheckShare(std::string_view field, double value) { CheckWithin(field, value, 0.0, 1.0); }

void CheckAtLeast(std::string_view field, int64_t value, int64_t low) {
  if (value < low) {
    throw OptionError(std::string(field), fmt::format("expected >= {}, got {}", low, value));
  }
}

void CheckOrdered(std::string_view min_field, double min, std::string_view max_field, double max) {
  if (!(max >= min)) {
    throw OptionError(std::string(max_field),
                      fmt::format("expected >= {} ({}), got {}", min_field, min, max));
  }
}

}  // namespace simtree::reconstruction
