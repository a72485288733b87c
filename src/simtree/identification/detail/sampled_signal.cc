#include "simtree/identification/detail/sampled_signal.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::identification {

int SampledSignal::valid_count() const {
  return static_cast<int>(std::count(valid.begin(), valid.end(), true));
}

int SampledSignal::longest_gap() const {
  int longest = 0, run = 0;
  for (bool v : valid) {
    run = v ? 0 : run + 1;
    longest = std::max(longest, run);
  }
  return longest;
}

SampledSignal SampledSignal::Slice(int begin, int end) const {
  begin = std::clamp(begin, 0, size());
  end = std::clamp(end, begin, size());
  SampledSignal out;
  out.start_time_s = time_at(begin);
  out.dt = dt;
  out.values = values.middleRows(begin, end - begin);
  out.valid.assign(valid.begin() + begin, valid.begin() + end);
  out.channel_names = channel_names;
  return out;
}

SampledSignal SampledSignal::TrimInvalidEnds() const {
  int begin = 0, end = size();
  while (begin < end && !valid[begin]) ++begin;
  while (end > begin && !valid[end - 1]) --end;
  return Slice(begin, end);
}

Eigen::MatrixXd SampledSignal::FilledValues() const {
  Eigen::MatrixXd out = values;
  const int n = size();
  int last_valid = -1;
  for (int i = 0; i < n; ++i) {
    if (!valid[i]) continue;
    if (last_valid >= 0 && i - last_valid > 1) {
      for (int k = last_valid + 1; k < i; ++k) {
        const double a = double(k - last_valid) / (i - last_valid);
        out.row(k) = (1 - a) * values.row(last_valid) + a * values.row(i);
      }
    }
    last_valid = i;
  }
  // Ends without a valid neighbour on one side hold the nearest valid value.
  int first_valid = 0;
  while (first_valid < n && !valid[first_valid]) ++first_valid;
  if (first_valid == n) return out;
  for (int k = 0; k < first_valid; ++k) out.row(k) = values.row(first_valid);
  for (int k = last_valid + 1; k < n; ++k) out.row(k) = values.row(last_valid);
  return out;
}

SampledSignal ResampleOnGrid(const std::vector<double>& times, const Eigen::MatrixXd& values,
                             const std::vector<bool>& valid, const std::string& source) {
  const size_t n = times.size();
  if (n < 2 || values.rows() != static_cast<Eigen::Index>(n) || valid.size() != n) {
    throw InputError(source, "",
                     fmt::format("expected at least 2 samples with one value row and "
                                 "one flag each, got {} times",
                                 n));
  }
  std::vector<double> steps(n - 1);
  for (size_t i = 1; i < n; ++i) steps[i - 1] = times[i] - times[i - 1];
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double dt = steps[steps.size() / 2];
  if (!(dt > 0)) throw InputError(source, "", "expected increasing sample times");
  const double span = times.back() - times.front();
  const int count = static_cast<int>(std::lround(span / dt)) + 1;
  SampledSignal out;
  out.start_time_s = times.front();
  out.dt = dt;
  out.values =
      Eigen::MatrixXd::Constant(count, values.cols(), std::numeric_limits<double>::quiet_NaN());
  out.valid.assign(count, false);
  for (size_t i = 0; i < n; ++i) {
    const double k_real = (times[i] - times.front()) / dt;
    const long k = std::lround(k_real);
    if (std::abs(k_real - k) > 0.25 || k < 0 || k >= count) {
      throw InputError(source, fmt::format("time {:.6f} s", times[i]),
                       fmt::format("expected samples every {:.6f} s (the median step); this one "
                                   "is {:.2f} steps from the grid",
                                   dt, std::abs(k_real - k)));
    }
    if (valid[i] && values.row(i).allFinite()) {
      out.values.row(k) = values.row(i);
      out.valid[k] = true;
    }
  }
  return out;
}

Eigen::VectorXd EstimateNoiseLevel(const SampledSignal& signal) {
  Eigen::VectorXd noise = Eigen::VectorXd::Zero(signal.channels());
  for (int c = 0; c < signal.channels(); ++c) {
    std::vector<double> d2;
    for (int i = 1; i + 1 < signal.size(); ++i) {
      if (!signal.valid[i - 1] || !signal.valid[i] || !signal.valid[i + 1]) continue;
      d2.push_back(
          std::abs(signal.values(i + 1, c) - 2 * signal.values(i, c) + signal.values(i - 1, c)));
    }
    if (d2.empty()) continue;
    std::nth_element(d2.begin(), d2.begin() + d2.size() / 2, d2.end());
    noise[c] = d2[d2.size() / 2] / 0.6745 / std::sqrt(6.0);
  }
  return noise;
}

}  // namespace simtree::identification
