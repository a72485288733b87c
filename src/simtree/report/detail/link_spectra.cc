#include "simtree/report/detail/link_spectra.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "simtree/identification/estimators.h"
#include "simtree/identification/identify.h"

namespace simtree::report {
namespace {

namespace id = simtree::identification;

// The marker list behind the links: each link's child, with the label the link gives it.
std::vector<MarkerLink> MarkersOf(const id::MaterialsFile& materials, bool* has_root) {
  std::map<int, std::string> labels;
  std::map<int, int> parent_of;
  for (const id::LinkMaterial& l : materials.links) {
    parent_of[l.child] = l.parent;
    if (l.parent < 0) labels[l.child] = l.label;
  }
  std::vector<MarkerLink> markers;
  *has_root = false;
  for (const id::LinkMaterial& l : materials.links) {
    std::string label = fmt::format("M{}", l.child);
    const auto parent_label = labels.find(l.parent);
    if (l.parent < 0) {
      label = l.label;
      *has_root = true;
    } else if (parent_label != labels.end() && l.label.rfind(parent_label->second + "-", 0) == 0) {
      label = l.label.substr(parent_label->second.size() + 1);
    }
    markers.push_back({l.child, label, l.parent, l.branch});
  }
  // A parent that is no link's child is the root marker (identify ran without the root's link).
  for (const id::LinkMaterial& l : materials.links) {
    if (l.parent >= 0 && !parent_of.count(l.parent)) {
      markers.push_back({l.parent, fmt::format("M{}", l.parent), -1, std::nullopt});
      parent_of[l.parent] = -1;
    }
  }
  return markers;
}

LinkSpectrum SpectrumOf(const id::LinkIdentification& link, const id::LinkMaterial* material,
                        int max_bins) {
  LinkSpectrum out;
  out.label = link.deflection.link.label;
  out.unit = link.deflection.kind == id::DeflectionKind::kDisplacement ? "m" : "rad";
  if (material) {
    out.label = material->label;
    out.status = id::ToString(material->value.status);
    out.frequency_hz = material->value.frequency_hz;
    out.damping_ratio = material->value.damping_ratio;
  }
  const id::SampledSignal& s = link.deflection.signal;
  if (!link.deflection.problem.empty() || s.size() < 4 || s.valid_count() < 4) {
    out.problem = link.deflection.problem.empty() ? "too few samples" : link.deflection.problem;
    return out;
  }
  out.channel_names = s.channel_names;
  const Eigen::MatrixXd filled = s.TrimInvalidEnds().FilledValues();
  const double f_dom = std::isfinite(out.frequency_hz) ? out.frequency_hz : 1.0;
  const double f_max = std::min(0.5 / s.dt, std::max(4.0, 3.0 * f_dom));
  id::SpectrumOptions options;
  options.zero_pad_factor = 8;
  for (int c = 0; c < filled.cols(); ++c) {
    const id::AmplitudeSpectrum spectrum = id::ComputeAmplitudeSpectrum(
        std::vector<double>(filled.col(c).data(), filled.col(c).data() + filled.rows()), s.dt,
        options);
    const int bins = std::min(spectrum.size(), static_cast<int>(f_max / spectrum.bin_hz) + 1);
    const int step = std::max(1, (bins + max_bins - 1) / std::max(max_bins, 1));
    out.bin_hz = spectrum.bin_hz * step;
    std::vector<double> kept;
    for (int k = 0; k < bins; k += step) kept.push_back(spectrum.amplitude[k]);
    out.amplitude.push_back(std::move(kept));
  }
  return out;
}

}  // namespace

std::vector<LinkSpectrum> ComputeLinkSpectra(const Trajectories& trajectories,
                                             const id::MaterialsFile& materials, int max_bins) {
  bool has_root = false;
  const std::vector<MarkerLink> markers = MarkersOf(materials, &has_root);
  id::IdentifyOptions options;
  options.estimator = id::EstimatorKind::kHalfPowerFft;  // the cheapest; only the signals are used
  options.compare_estimators = false;
  options.joint_poles = false;
  options.include_root = has_root;
  if (materials.window_end_s > materials.window_start_s) {
    options.release_time_s = materials.window_start_s;
    options.window_s = materials.window_end_s - materials.window_start_s;
  }
  const id::IdentificationResult result =
      id::IdentifyMaterials(trajectories, markers, options, materials.trajectories);
  std::vector<LinkSpectrum> out;
  for (const id::LinkIdentification& link : result.links) {
    const id::LinkMaterial* material = nullptr;
    for (const id::LinkMaterial& m : materials.links) {
      if (m.child == link.deflection.link.child && m.parent == link.deflection.link.parent) {
        material = &m;
      }
    }
    out.push_back(SpectrumOf(link, material, max_bins));
  }
  return out;
}

nlohmann::json SpectraJson(const std::vector<LinkSpectrum>& spectra) {
  nlohmann::json links = nlohmann::json::array();
  for (const LinkSpectrum& s : spectra) {
    nlohmann::json channels = nlohmann::json::array();
    for (size_t c = 0; c < s.amplitude.size(); ++c) {
      nlohmann::json values = nlohmann::json::array();
      // In milli-units with 4 decimals: short numbers in the page.
      for (double a : s.amplitude[c]) values.push_back(std::round(a * 1e7) / 1e4);
      channels.push_back({{"name", c < s.channel_names.size() ? s.channel_names[c] : ""},
                          {"amplitude", std::move(values)}});
    }
    links.push_back(
        {{"label", s.label},
         {"status", s.status},
         {"unit", s.unit == "m" ? "mm" : "mrad"},
         {"frequency_hz",
          std::isfinite(s.frequency_hz) ? nlohmann::json(s.frequency_hz) : nlohmann::json()},
         {"damping_ratio",
          std::isfinite(s.damping_ratio) ? nlohmann::json(s.damping_ratio) : nlohmann::json()},
         {"bin_hz", s.bin_hz},
         {"channels", std::move(channels)},
         {"problem", s.problem}});
  }
  return {{"links", std::move(links)}};
}

}  // namespace simtree::report
