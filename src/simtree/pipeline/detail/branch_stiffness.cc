#include "simtree/pipeline/detail/branch_stiffness.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::pipeline::detail {

void StiffnessCalibrationOptions::Validate() const {
  constexpr const char* kSource = "stiffness calibration options";
  CheckOption(!factors.empty(), kSource, "factors", "expected at least one factor");
  for (size_t i = 0; i < factors.size(); ++i) {
    CheckOption(
        factors[i] >= 1.0 && std::isfinite(factors[i]) && (i == 0 || factors[i] > factors[i - 1]),
        kSource, "factors",
        fmt::format("expected increasing finite factors >= 1, got {} at {}", factors[i], i));
  }
  CheckOption(tolerance >= 0.0 && std::isfinite(tolerance), kSource, "tolerance",
              "expected a share >= 0");
}

Tree StiffenBranches(const Tree& tree, double factor) {
  Tree out = tree;
  if (factor == 1.0) return out;
  for (Branch& b : out.branches) {
    if (b.level < 1 || !b.material) continue;
    for (Mode& m : b.material->modes) m.frequency_hz *= factor;
    b.material->stiffness *= factor * factor;
  }
  return out;
}

StiffnessCalibration CalibrateBranchStiffness(const Tree& tree, const Trajectories& tracks,
                                              const Eigen::Isometry3d& world_from_camera,
                                              double release_s, const std::vector<int>& excluded,
                                              const PullFitOptions& fit_options,
                                              const StiffnessCalibrationOptions& options) {
  options.Validate();
  std::vector<std::optional<PullFit>> fits;
  StiffnessCalibration out;
  std::optional<InputError> first_error;
  double best = std::numeric_limits<double>::infinity();
  for (const double factor : options.factors) {
    try {
      const PullFit fit = FitPull(StiffenBranches(tree, factor), tracks, world_from_camera,
                                  release_s, excluded, fit_options);
      const double residual = fit.motion.fitted ? fit.motion.residual_rms_m : fit.residual_rms_m;
      out.trials.push_back({factor, residual});
      fits.emplace_back(fit);
      best = std::min(best, residual);
      spdlog::debug("stiffness factor {}: replay residual {:.1f} mm", factor, 1e3 * residual);
    } catch (const InputError& e) {
      if (!first_error) first_error = e;
      out.trials.push_back({factor, std::numeric_limits<double>::infinity()});
      fits.emplace_back();
    }
  }
  if (!std::isfinite(best)) throw *first_error;
  for (size_t i = 0; i < out.trials.size(); ++i) {
    if (out.trials[i].residual_rms_m <= (1.0 + options.tolerance) * best) {
      out.factor = out.trials[i].factor;
      out.fit = *fits[i];
      break;
    }
  }
  return out;
}

}  // namespace simtree::pipeline::detail
