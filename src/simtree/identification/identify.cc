#include "simtree/identification/identify.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"

namespace simtree {

const SignalEstimate* LinkIdentification::Find(EstimatorKind kind) const {
  for (const SignalEstimate& e : estimates) {
    if (e.estimator == kind) return &e;
  }
  return nullptr;
}

MaterialRanges IdentificationResult::Ranges(std::optional<EstimatorKind> kind) const {
  MaterialRanges r;
  std::vector<double> f, z;
  for (const LinkIdentification& link : links) {
    ++r.links;
    const ModalEstimate* e = &link.value;
    if (kind) {
      const SignalEstimate* s = link.Find(*kind);
      e = s ? &s->dominant : nullptr;
    }
    if (!e || e->status != EstimateStatus::kOk) continue;
    ++r.measured;
    f.push_back(e->frequency_hz);
    z.push_back(e->damping_ratio);
  }
  if (!f.empty()) {
    r.min_frequency_hz = *std::min_element(f.begin(), f.end());
    r.max_frequency_hz = *std::max_element(f.begin(), f.end());
    r.min_damping = *std::min_element(z.begin(), z.end());
    r.max_damping = *std::max_element(z.begin(), z.end());
  }
  return r;
}

IdentificationResult IdentifyMaterials(const Trajectories& input,
                                       const std::vector<MarkerLink>& markers,
                                       const IdentifyOptions& options, const std::string& source) {
  IdentificationResult out;
  Trajectories trajectories = input;
  if (options.remove_outliers) {
    out.outliers = RemoveTrackOutliers(trajectories, options.outliers);
    if (out.outliers.removed > 0) spdlog::info("{}: {}", source, out.outliers.note);
  }
  out.estimator = options.estimator;
  if (trajectories.frame_count() < 2) {
    throw InputError(source, "", "expected at least 2 frames of trajectories");
  }
  std::set<int> listed;
  int tracked = 0;
  for (const MarkerLink& m : markers) {
    listed.insert(m.id);
    tracked += trajectories.Find(m.id) != nullptr;
  }
  if (tracked == 0) {
    throw InputError(source, "",
                     fmt::format("none of the {} markers of the marker list has a trajectory "
                                 "(the trajectories hold markers {})",
                                 markers.size(), [&] {
                                   std::string ids;
                                   for (const MarkerTrack& t : trajectories.tracks) {
                                     ids += (ids.empty() ? "" : ", ") + std::to_string(t.marker);
                                   }
                                   return ids;
                                 }()));
  }
  for (const MarkerTrack& track : trajectories.tracks) {
    if (!listed.count(track.marker)) {
      spdlog::warn("{}: marker {} is not in the marker list; it is ignored", source, track.marker);
    }
  }
  const int n = trajectories.frame_count();
  out.frame_rate_hz = (n - 1) / (trajectories.times_s.back() - trajectories.times_s.front());

  // The free decay: from the release to the end, or `window_s` long.
  int first = 0;
  if (options.release_time_s) {
    first = FrameAtOrAfter(trajectories, *options.release_time_s);
    if (first >= n) {
      throw InputError(source, "",
                       fmt::format("the release time {:.3f} s is after the last frame "
                                   "({:.3f} s)",
                                   *options.release_time_s, trajectories.times_s.back()));
    }
    out.release.found = true;
    out.release.frame_index = first;
    out.release.time_s = trajectories.times_s[first];
    out.release.note = fmt::format("release given at {:.3f} s", *options.release_time_s);
  } else {
    out.release = DetectRelease(trajectories, options.release);
    first = out.release.frame_index;
  }
  int end = n;
  if (options.window_s > 0) {
    end = std::min(n, FrameAtOrAfter(trajectories, trajectories.times_s[first] + options.window_s));
  }
  out.window_start_s = trajectories.times_s[first];
  out.window_end_s = trajectories.times_s[std::max(first, end - 1)];

  std::vector<EstimatorKind> kinds = {options.estimator};
  if (options.compare_estimators) {
    for (EstimatorKind k : AllEstimators()) {
      if (k != options.estimator) kinds.push_back(k);
    }
  }
  const std::vector<DeflectionLink> links = LinksFromMarkers(markers, options.include_root);
  for (DeflectionSignal& deflection :
       ComputeDeflectionSignals(trajectories, links, first, end, options.deflection)) {
    LinkIdentification link;
    if (!deflection.problem.empty()) {
      link.value.status = EstimateStatus::kMissingMarker;
      link.value.message = deflection.problem;
    } else {
      for (EstimatorKind kind : kinds) {
        link.estimates.push_back(EstimateModes(deflection.signal, kind, options.estimation));
      }
      link.value = link.estimates.front().dominant;
    }
    link.deflection = std::move(deflection);
    out.links.push_back(std::move(link));
  }
  return out;
}

namespace {

std::string Value(double x, const char* format) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : "-";
}

}  // namespace

std::string FormatRanges(const MaterialRanges& r, const std::string& name) {
  if (r.measured == 0) {
    return fmt::format("{:<22} no link measured ({} links)", name, r.links);
  }
  return fmt::format("{:<22} f {:.2f}~{:.2f} Hz   zeta {:.3f}~{:.3f}   ({} of {} links measured)",
                     name, r.min_frequency_hz, r.max_frequency_hz, r.min_damping, r.max_damping,
                     r.measured, r.links);
}

std::string FormatLinkTable(const IdentificationResult& result) {
  std::string out = fmt::format("{:<14} {:<14} {:>16} {:>16}", "link", "status", "f (Hz)", "zeta");
  std::vector<EstimatorKind> others;
  if (!result.links.empty()) {
    for (const SignalEstimate& e : result.links.front().estimates) {
      if (e.estimator != result.estimator) others.push_back(e.estimator);
    }
  }
  for (EstimatorKind k : others) out += fmt::format("   {:>24}", ToString(k));
  out += "\n";
  for (const LinkIdentification& link : result.links) {
    const ModalEstimate& v = link.value;
    std::string f = Value(v.frequency_hz, "{:.4f}");
    std::string z = Value(v.damping_ratio, "{:.4f}");
    if (std::isfinite(v.frequency_std_hz)) f += Value(v.frequency_std_hz, "±{:.4f}");
    if (std::isfinite(v.damping_std)) z += Value(v.damping_std, "±{:.4f}");
    out += fmt::format("{:<14} {:<14} {:>16} {:>16}", link.deflection.link.label,
                       ToString(v.status), f, z);
    for (EstimatorKind k : others) {
      const SignalEstimate* e = link.Find(k);
      const std::string cell = e ? Value(e->dominant.frequency_hz, "{:.3f}") + " / " +
                                       Value(e->dominant.damping_ratio, "{:.4f}")
                                 : "-";
      out += fmt::format("   {:>24}", cell);
    }
    if (v.status != EstimateStatus::kOk && !v.message.empty()) out += "   " + v.message;
    out += "\n";
  }
  return out;
}

}  // namespace simtree
