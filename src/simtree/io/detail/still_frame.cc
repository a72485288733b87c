#include "simtree/io/detail/still_frame.h"

#include <algorithm>
#include <cmath>

namespace simtree::azure_detail {

SmallGrey Shrink(const RgbImage& color) {
  SmallGrey g;
  g.width = color.width / 4;
  g.height = color.height / 4;
  g.values.assign(static_cast<size_t>(g.width) * g.height, 0.0f);
  for (int y = 0; y < g.height * 4; ++y) {
    for (int x = 0; x < g.width * 4; ++x) {
      g.values[static_cast<size_t>(y / 4) * g.width + x / 4] += color.at(x, y, 1) / 16.0f;
    }
  }
  return g;
}

double Sharpness(const RgbImage& color) {
  double sum = 0, sum2 = 0;
  int64_t n = 0;
  for (int y = 1; y + 1 < color.height; ++y) {
    for (int x = 1; x + 1 < color.width; ++x) {
      const double lap = 4.0 * color.at(x, y, 1) - color.at(x - 1, y, 1) - color.at(x + 1, y, 1) -
                         color.at(x, y - 1, 1) - color.at(x, y + 1, 1);
      sum += lap;
      sum2 += lap * lap;
      ++n;
    }
  }
  if (n == 0) return 0;
  const double mean = sum / n;
  return sum2 / n - mean * mean;
}

double Motion(const SmallGrey& a, const SmallGrey& b) {
  double sum = 0;
  for (size_t i = 0; i < a.values.size(); ++i) sum += std::abs(a.values[i] - b.values[i]);
  return a.values.empty() ? 0.0 : sum / a.values.size();
}

int PickStill(const std::vector<double>& sharpness, const std::vector<double>& motion,
              double still_motion, int* still_count) {
  const int n = static_cast<int>(sharpness.size());
  std::vector<double> sorted = motion;
  std::sort(sorted.begin(), sorted.end());
  const double quarter = sorted.empty() ? 0.0 : sorted[(sorted.size() - 1) / 4];
  const double limit = std::max(still_motion, quarter);
  int best = -1;
  int still = 0;
  for (int i = 0; i < n; ++i) {
    if (motion[i] > limit) continue;
    ++still;
    if (best < 0 || sharpness[i] > sharpness[best]) best = i;
  }
  if (still_count) *still_count = still;
  return best;
}

}  // namespace simtree::azure_detail
