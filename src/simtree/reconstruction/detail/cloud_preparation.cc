#include "simtree/reconstruction/detail/cloud_preparation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::reconstruction {
namespace {

// The unit a too-tall cloud most likely is in, with the factor that brings it to metres.
struct UnitGuess {
  const char* name;
  double to_metres;
};
UnitGuess GuessUnit(double height) {
  for (const UnitGuess guess : {UnitGuess{"millimetres", 0.001}, UnitGuess{"centimetres", 0.01},
                                UnitGuess{"inches", 0.0254}, UnitGuess{"feet", 0.3048}}) {
    const double metres = height * guess.to_metres;
    if (metres >= 0.5 && metres <= 40.0) return guess;
  }
  return {"an unknown unit", 0.0};
}

// Indices of points that repeat an earlier point within `tolerance` (same quantized cell, which
// catches exact copies and float round trips of one point).
std::vector<char> DuplicateFlags(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  using Key = std::array<int64_t, 3>;
  std::vector<std::pair<Key, size_t>> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = (points[i] / tolerance).array().round();
    keys[i] = {
        Key{static_cast<int64_t>(q.x()), static_cast<int64_t>(q.y()), static_cast<int64_t>(q.z())},
        i};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> duplicate(points.size(), 0);
  for (size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].first == keys[k - 1].first) duplicate[keys[k].second] = 1;
  }
  return duplicate;
}

}  // namespace

Eigen::Vector3d TrimmedExtent(std::span<const Eigen::Vector3d> points, double trim) {
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();
  if (points.empty()) return extent;
  std::vector<double> values(points.size());
  const size_t lo = static_cast<size_t>(trim * (points.size() - 1));
  const size_t hi = points.size() - 1 - lo;
  for (int axis = 0; axis < 3; ++axis) {
    for (size_t i = 0; i < points.size(); ++i) values[i] = points[i][axis];
    std::nth_element(values.begin(), values.begin() + lo, values.end());
    const double low = values[lo];
    std::nth_element(values.begin(), values.begin() + hi, values.end());
    extent[axis] = values[hi] - low;
  }
  return extent;
}

void CloudPreparationOptions::Validate() const {
  CheckPositive("scale", scale);
  CheckNonNegative("duplicate_tolerance_m", duplicate_tolerance_m);
  CheckPositive("max_height_m", max_height_m);
  CheckNonNegative("min_height_m", min_height_m);
  CheckOrdered("min_height_m", min_height_m, "max_height_m", max_height_m);
  CheckNonNegative("min_height_to_width", min_height_to_width);
  CheckInRange("extent_trim", extent_trim, 0.0, 0.5);
}

PreparedCloud PrepareCloud(std::span<const Eigen::Vector3d> points, const std::string& source,
                           const CloudPreparationOptions& options) {
  options.Validate();
  PreparedCloud out;
  out.input_points = points.size();
  if (points.empty()) throw InputError(source, "", "the cloud has no points");
  auto warn = [&](std::string message) {
    spdlog::warn("{}: {}", source, message);
    out.warnings.push_back(std::move(message));
  };

  out.points.reserve(points.size());
  size_t first_bad = points.size();
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].allFinite()) {
      out.points.push_back(points[i] * options.scale);
    } else {
      if (first_bad == points.size()) first_bad = i;
      ++out.dropped_non_finite;
    }
  }
  if (out.points.empty()) {
    throw InputError(source, "", "no point has finite coordinates (all NaN or infinite)");
  }
  if (out.dropped_non_finite > 0) {
    warn(fmt::format("dropped {} point{} with NaN or infinite coordinates (the first is point {})",
                     out.dropped_non_finite, out.dropped_non_finite == 1 ? "" : "s", first_bad));
  }

  const std::vector<char> duplicate = DuplicateFlags(out.points, options.duplicate_tolerance_m);
  out.dropped_duplicates = std::count(duplicate.begin(), duplicate.end(), 1);
  if (out.dropped_duplicates > 0) {
    std::vector<Eigen::Vector3d> unique;
    unique.reserve(out.points.size() - out.dropped_duplicates);
    for (size_t i = 0; i < out.points.size(); ++i) {
      if (!duplicate[i]) unique.push_back(out.points[i]);
    }
    out.points = std::move(unique);
    warn(fmt::format(
        "dropped {} duplicated points ({:.0f}% of the cloud{})", out.dropped_duplicates,
        100.0 * out.dropped_duplicates / (out.points.size() + out.dropped_duplicates),
        out.dropped_duplicates * 2 >= out.points.size() ? ": was the same scan merged twice?"
                                                        : ""));
  }

  out.extent = TrimmedExtent(out.points, options.extent_trim);
  const double height = out.extent.z();
  const double width = std::max(out.extent.x(), out.extent.y());
  if (height > options.max_height_m) {
    const UnitGuess unit = GuessUnit(height);
    throw InputError(
        source, "units",
        unit.to_metres > 0.0
            ? fmt::format("the cloud is {:.4g} units tall, which would be a {:.4g} m tree: it "
                          "looks like {}; simtree wants metres (rescale it, or pass --scale {:g})",
                          height, height, unit.name, unit.to_metres)
            : fmt::format("the cloud is {:.4g} units tall; expected metres (a tree under {:g} m)",
                          height, options.max_height_m));
  }
  if (height < options.min_height_m || height < options.min_height_to_width * width) {
    throw InputError(
        source, "shape",
        fmt::format("no vertical structure: the cloud is {:.3g} x {:.3g} m wide but {:.3g} m "
                    "tall; expected a standing tree with Z up (at least {:g} m and {:.0f}% of "
                    "its width tall)",
                    out.extent.x(), out.extent.y(), height, options.min_height_m,
                    100.0 * options.min_height_to_width));
  }
  if (points.size() > 0 && out.points.size() < 50) {
    warn(fmt::format("only {} points: the reconstruction will be coarse", out.points.size()));
  }
  return out;
}

}  // namespace simtree::reconstruction
