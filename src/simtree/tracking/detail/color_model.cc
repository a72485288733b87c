#include "simtree/tracking/detail/color_model.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::tracking::detail {
namespace {

float Clamp01(float x) { return std::min(1.0f, std::max(0.0f, x)); }

// Median of angles (degrees) that lie within 90 degrees of `around`: unwrapped about it first.
double CircularMedian(std::vector<double> hues, double around) {
  for (double& h : hues) {
    double d = h - around;
    while (d > 180.0) d -= 360.0;
    while (d < -180.0) d += 360.0;
    h = d;
  }
  std::nth_element(hues.begin(), hues.begin() + hues.size() / 2, hues.end());
  double median = around + hues[hues.size() / 2];
  while (median < 0.0) median += 360.0;
  while (median >= 360.0) median -= 360.0;
  return median;
}

double Quantile(std::vector<double> values, double q) {
  const size_t k = std::min(values.size() - 1, static_cast<size_t>(q * values.size()));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

}  // namespace

void RgbToHsv(uint8_t r, uint8_t g, uint8_t b, float* hue_deg, float* saturation, float* value) {
  const int mx = std::max({r, g, b});
  const int mn = std::min({r, g, b});
  const float chroma = static_cast<float>(mx - mn);
  *value = static_cast<float>(mx);
  *saturation = mx == 0 ? 0.0f : chroma / static_cast<float>(mx);
  if (chroma <= 0.0f) {
    *hue_deg = 0.0f;
    return;
  }
  float h;
  if (mx == r) {
    h = static_cast<float>(g - b) / chroma;
    if (h < 0.0f) h += 6.0f;
  } else if (mx == g) {
    h = static_cast<float>(b - r) / chroma + 2.0f;
  } else {
    h = static_cast<float>(r - g) / chroma + 4.0f;
  }
  *hue_deg = 60.0f * h;
}

double HueDistance(double a_deg, double b_deg) {
  double d = std::fmod(std::abs(a_deg - b_deg), 360.0);
  return d > 180.0 ? 360.0 - d : d;
}

double TapeColorModel::MinSaturationAt(double hue_distance_deg) const {
  if (hue_distance_deg <= hue_core_deg || hue_tolerance_deg <= hue_core_deg) return min_saturation;
  const double t =
      std::min(1.0, (hue_distance_deg - hue_core_deg) / (hue_tolerance_deg - hue_core_deg));
  return min_saturation + t * std::max(0.0, edge_saturation - min_saturation);
}

double TapeColorModel::EffectiveHueDistance(double hue) const {
  double signed_d = std::fmod(hue - hue_deg + 540.0, 360.0) - 180.0;  // (-180, 180]
  if (extra_hue_deg > 0.0 && signed_d * extra_side > 0.0) {
    signed_d = std::max(0.0, std::abs(signed_d) - extra_hue_deg);
  }
  return std::abs(signed_d);
}

bool TapeColorModel::Contains(uint8_t r, uint8_t g, uint8_t b) const {
  float h, s, v;
  RgbToHsv(r, g, b, &h, &s, &v);
  if (v < min_value) return false;
  const double d = EffectiveHueDistance(h);
  return d <= hue_tolerance_deg && s >= MinSaturationAt(d);
}

float TapeColorModel::Weight(uint8_t r, uint8_t g, uint8_t b) const {
  float h, s, v;
  RgbToHsv(r, g, b, &h, &s, &v);
  if (v < 0.5 * min_value) return 0.0f;
  const double d = EffectiveHueDistance(h);
  const double least = MinSaturationAt(std::min(d, hue_tolerance_deg));
  const float low = static_cast<float>(0.7 * least);
  const float full = static_cast<float>(std::max(full_saturation, least + 0.05));
  const float sat = Clamp01((s - low) / (full - low));
  const double hue_out = d - hue_tolerance_deg;
  const float hue = hue_out <= 0.0 ? 1.0f : Clamp01(1.0f - static_cast<float>(hue_out / 10.0));
  const float val = Clamp01(static_cast<float>((v - 0.5 * min_value) / (0.5 * min_value)));
  return sat * hue * val;
}

std::string TapeColorModel::Describe() const {
  return fmt::format(
      "hue {:.0f} +- {:.0f} deg ({:+.0f} deg on the {} side), saturation >= {:.2f} (all tape "
      "from {:.2f}), value >= {:.0f}",
      hue_deg, hue_tolerance_deg, extra_hue_deg, extra_side > 0 ? "larger-hue" : "smaller-hue",
      min_saturation, full_saturation, min_value);
}

TapeColorModel ColorModelFromName(const std::string& name) {
  static const std::map<std::string, double> kHues = {{"auto", 0.0},    {"red", 0.0},
                                                      {"orange", 28.0}, {"yellow", 55.0},
                                                      {"green", 120.0}, {"blue", 225.0}};
  TapeColorModel model;
  if (auto it = kHues.find(name); it != kHues.end()) {
    model.hue_deg = it->second;
    return model;
  }
  const bool hex =
      name.size() == 7 && name[0] == '#' &&
      std::all_of(name.begin() + 1, name.end(), [](char c) { return std::isxdigit(c); });
  if (!hex) {
    throw InputError("--color", "",
                     fmt::format("expected auto, red, orange, yellow, green, blue or #rrggbb, got "
                                 "'{}'",
                                 name));
  }
  const unsigned long rgb = std::stoul(name.substr(1), nullptr, 16);
  float h, s, v;
  RgbToHsv(static_cast<uint8_t>(rgb >> 16), static_cast<uint8_t>(rgb >> 8),
           static_cast<uint8_t>(rgb), &h, &s, &v);
  if (s < 0.3f) {
    throw InputError("--color", "",
                     fmt::format("'{}' is too grey to tell a tape from bark (saturation {:.2f}; "
                                 "at least 0.30)",
                                 name, s));
  }
  model.hue_deg = h;
  return model;
}

TapeColorModel FitColorModel(const TapeColorModel& prior, const RgbImage& image,
                             const std::vector<Eigen::Vector2d>& pixels, int radius,
                             int min_samples, int* samples_found) {
  std::vector<double> hues, sats, values;
  for (const Eigen::Vector2d& p : pixels) {
    const int u0 = static_cast<int>(std::lround(p.x()));
    const int v0 = static_cast<int>(std::lround(p.y()));
    for (int y = std::max(0, v0 - radius); y <= std::min(image.height - 1, v0 + radius); ++y) {
      for (int x = std::max(0, u0 - radius); x <= std::min(image.width - 1, u0 + radius); ++x) {
        float h, s, v;
        RgbToHsv(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), &h, &s, &v);
        // Tape by the prior: the window also holds bark, which may be reddish.
        if (!prior.Contains(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2))) continue;
        hues.push_back(h);
        sats.push_back(s);
        values.push_back(v);
      }
    }
  }
  if (samples_found) *samples_found = static_cast<int>(hues.size());
  if (static_cast<int>(hues.size()) < min_samples) return prior;
  TapeColorModel model = prior;
  model.hue_deg = CircularMedian(hues, prior.hue_deg);
  std::vector<double> spread;
  spread.reserve(hues.size());
  for (double h : hues) spread.push_back(HueDistance(h, model.hue_deg));
  model.hue_tolerance_deg = std::clamp(1.5 * Quantile(spread, 0.95), 12.0, prior.hue_tolerance_deg);
  model.min_saturation = std::clamp(0.6 * Quantile(sats, 0.1), prior.min_saturation, 0.6);
  model.full_saturation = std::clamp(Quantile(sats, 0.5), model.min_saturation + 0.05, 0.95);
  model.min_value = std::clamp(0.5 * Quantile(values, 0.1), 12.0, prior.min_value);
  return ExtendAwayFromBackground(model, image, pixels, radius);
}

TapeColorModel ExtendAwayFromBackground(const TapeColorModel& model, const RgbImage& image,
                                        const std::vector<Eigen::Vector2d>& pixels, int radius,
                                        double max_extra_deg) {
  constexpr double kLooseHueDeg = 60.0;
  constexpr double kBackgroundSaturation = 0.15;  // below it a pixel's hue is noise
  const auto signed_hue = [&](float h) {
    return std::fmod(h - model.hue_deg + 540.0, 360.0) - 180.0;
  };
  std::vector<double> tape_hues, background;
  // The background near the tape's hue: the scene's weakly saturated pixels within the loose
  // interval (bark, for a red tape orange-brown), over the whole frame so the few tape pixels
  // mixed with sky do not decide.
  for (int y = 0; y < image.height; y += 2) {
    for (int x = 0; x < image.width; x += 2) {
      float h, s, v;
      RgbToHsv(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), &h, &s, &v);
      const double sh = signed_hue(h);
      if (std::abs(sh) <= kLooseHueDeg && s >= kBackgroundSaturation && s < model.min_saturation &&
          v >= model.min_value) {
        background.push_back(sh);
      }
    }
  }
  for (const Eigen::Vector2d& p : pixels) {
    const int u0 = static_cast<int>(std::lround(p.x()));
    const int v0 = static_cast<int>(std::lround(p.y()));
    double best_s = -1.0, best_hue = 0.0;
    for (int y = std::max(0, v0 - radius); y <= std::min(image.height - 1, v0 + radius); ++y) {
      for (int x = std::max(0, u0 - radius); x <= std::min(image.width - 1, u0 + radius); ++x) {
        float h, s, v;
        RgbToHsv(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), &h, &s, &v);
        const double sh = signed_hue(h);
        if (std::abs(sh) > kLooseHueDeg || s < model.min_saturation || v < model.min_value)
          continue;
        if (s > best_s) {
          best_s = s;
          best_hue = sh;
        }
      }
    }
    if (best_s >= 0.0) tape_hues.push_back(best_hue);
  }
  if (tape_hues.empty() || background.empty()) return model;
  const int side = Quantile(background, 0.5) > 0.0 ? -1 : 1;
  double farthest = 0.0;
  for (double h : tape_hues) farthest = std::max(farthest, h * side);
  TapeColorModel out = model;
  out.extra_side = side;
  out.extra_hue_deg = std::clamp(farthest - model.hue_core_deg, 0.0, max_extra_deg);
  return out;
}

}  // namespace simtree::tracking::detail
