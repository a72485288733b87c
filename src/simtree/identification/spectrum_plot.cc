#include "simtree/identification/spectrum_plot.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::identification {
namespace {

const cv::Scalar kBlack(30, 30, 30), kGrey(200, 200, 200), kWhite(255, 255, 255);
// Channel colours (BGR): blue for u, orange for w; estimator colours.
const cv::Scalar kChannel[2] = {cv::Scalar(180, 100, 30), cv::Scalar(30, 130, 230)};
cv::Scalar EstimatorColour(EstimatorKind kind) {
  switch (kind) {
    case EstimatorKind::kHalfPowerFft:
      return cv::Scalar(40, 40, 200);  // red
    case EstimatorKind::kInterpolatedSpectrum:
      return cv::Scalar(160, 60, 160);  // purple
    case EstimatorKind::kDampedSinusoidFit:
      return cv::Scalar(40, 150, 40);  // green
  }
  return kBlack;
}

// A rectangle of the image with data ranges, mapping data to pixels.
struct Panel {
  cv::Rect box;
  double x0, x1, y0, y1;
  cv::Point At(double x, double y) const {
    const double u = (x - x0) / (x1 - x0), v = (y - y0) / (y1 - y0);
    return {box.x + static_cast<int>(std::lround(u * box.width)),
            box.y + box.height - static_cast<int>(std::lround(v * box.height))};
  }
};

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.45,
          const cv::Scalar& colour = kBlack) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

void Axes(cv::Mat& image, const Panel& p, const std::string& x_label, const std::string& y_label,
          double x_step) {
  cv::rectangle(image, p.box, kBlack, 1);
  for (double x = std::ceil(p.x0 / x_step) * x_step; x <= p.x1 + 1e-9; x += x_step) {
    const cv::Point a = p.At(x, p.y0);
    cv::line(image, a, {a.x, p.box.y}, kGrey, 1);
    Text(image, fmt::format("{:g}", x), {a.x - 8, a.y + 16}, 0.4);
  }
  Text(image, x_label, {p.box.x + p.box.width - 110, p.box.y + p.box.height + 34}, 0.45);
  Text(image, fmt::format("{:.3g}", p.y1), {4, p.box.y + 12}, 0.4);
  Text(image, fmt::format("{:.3g}", p.y0), {4, p.box.y + p.box.height}, 0.4);
  if (p.y0 < 0 && p.y1 > 0) {
    const cv::Point zero = p.At(p.x0, 0.0);
    cv::line(image, zero, {p.box.x + p.box.width, zero.y}, kGrey, 1);
    Text(image, "0", {40, zero.y + 4}, 0.4);
  }
  Text(image, y_label, {p.box.x, p.box.y - 6}, 0.45);
}

void Polyline(cv::Mat& image, const Panel& p, const std::vector<double>& x,
              const std::vector<double>& y, const cv::Scalar& colour, int thickness = 1) {
  std::vector<cv::Point> run;
  auto flush = [&] {
    if (run.size() > 1) cv::polylines(image, run, false, colour, thickness, cv::LINE_AA);
    run.clear();
  };
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(y[i]) || x[i] < p.x0 || x[i] > p.x1) {
      flush();
      continue;
    }
    run.push_back(p.At(x[i], std::clamp(y[i], p.y0, p.y1)));
  }
  flush();
}

std::string Format(const ModalEstimate& e) {
  if (e.status != EstimateStatus::kOk) {
    return fmt::format("{}{}", ToString(e.status), e.message.empty() ? "" : ": " + e.message);
  }
  std::string f = fmt::format("f {:.4f}", e.frequency_hz);
  if (std::isfinite(e.frequency_std_hz)) f += fmt::format(" +- {:.4f}", e.frequency_std_hz);
  std::string z = fmt::format("zeta {:.4f}", e.damping_ratio);
  if (std::isfinite(e.damping_std)) z += fmt::format(" +- {:.4f}", e.damping_std);
  return f + " Hz   " + z;
}

// Signals are drawn in mrad (angles) or mm (displacements).
constexpr double kScale = 1000.0;

std::string Unit(const DeflectionSignal& d) {
  return d.kind == DeflectionKind::kRelativeAngle ? "mrad" : "mm";
}

// The link's name and every estimator's value as text; returns the baseline of the last line.
int DrawHeader(cv::Mat& image, const IdentificationResult& result, const LinkIdentification& link) {
  const DeflectionLink& l = link.deflection.link;
  Text(image,
       fmt::format("link {}   ({} -> {}{})", l.label, l.parent, l.child,
                   l.branch ? fmt::format(", branch {}", *l.branch) : ""),
       {20, 26}, 0.6);
  int line = 50;
  Text(image, fmt::format("{}: {}", ToString(result.estimator), Format(link.value)), {20, line},
       0.5, EstimatorColour(result.estimator));
  for (const SignalEstimate& e : link.estimates) {
    if (e.estimator == result.estimator) continue;
    line += 20;
    Text(image, fmt::format("{}: {}", ToString(e.estimator), Format(e.dominant)), {20, line}, 0.45,
         EstimatorColour(e.estimator));
  }
  return line;
}

// The damped sinusoid fit's model of channel `c`, on the trimmed record the estimator saw (from
// its first valid sample).
void DrawModel(cv::Mat& image, const Panel& panel, const SampledSignal& s,
               const DampedSinusoidFit& fit, int c) {
  int first = 0;
  while (first < s.size() && !s.valid[first]) ++first;
  const SampledSignal trimmed = s.Slice(first, s.size());
  const Eigen::MatrixXd model = fit.Evaluate(trimmed);
  std::vector<double> ty(trimmed.size()), my(trimmed.size());
  for (int i = 0; i < trimmed.size(); ++i) {
    ty[i] = trimmed.time_at(i);
    my[i] = model(i, c) * kScale;
  }
  Polyline(image, panel, ty, my, EstimatorColour(EstimatorKind::kDampedSinusoidFit), 1);
}

// Top panel: both planes' deflection over time, the fitted model over them.
Panel DrawTimePanel(cv::Mat& image, const LinkIdentification& link, int line,
                    const SpectrumPlotOptions& options) {
  const DeflectionSignal& d = link.deflection;
  const SampledSignal& s = d.signal;
  Panel time{cv::Rect(70, line + 40, options.width - 100, (options.height - line - 160) / 2),
             s.start_time_s, s.start_time_s + s.duration_s(), 0, 0};
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < s.size(); ++i) {
    if (!s.valid[i]) continue;
    for (int c = 0; c < s.channels(); ++c) {
      lo = std::min(lo, s.values(i, c) * kScale);
      hi = std::max(hi, s.values(i, c) * kScale);
    }
  }
  if (!(hi > lo)) {
    lo -= 1;
    hi += 1;
  }
  time.y0 = lo - 0.05 * (hi - lo);
  time.y1 = hi + 0.05 * (hi - lo);
  Axes(image, time, "time (s)",
       fmt::format("{} ({}): {} blue, {} orange; model over it",
                   d.kind == DeflectionKind::kRelativeAngle ? "deflection" : "motion", Unit(d),
                   s.channel_names.size() > 0 ? s.channel_names[0] : "c0",
                   s.channel_names.size() > 1 ? s.channel_names[1] : "c1"),
       time.x1 - time.x0 > 12 ? 2.0 : 1.0);
  std::vector<double> t(s.size());
  for (int i = 0; i < s.size(); ++i) t[i] = s.time_at(i);
  const SignalEstimate* fit = link.Find(EstimatorKind::kDampedSinusoidFit);
  for (int c = 0; c < std::min(2, s.channels()); ++c) {
    std::vector<double> y(s.size());
    for (int i = 0; i < s.size(); ++i) y[i] = s.valid[i] ? s.values(i, c) * kScale : NAN;
    Polyline(image, time, t, y, kChannel[c], 1);
    if (fit && fit->fit) DrawModel(image, time, s, *fit->fit, c);
  }
  return time;
}

// Each estimator's frequency as a vertical line, and the paper's half-power band on its own
// (unpadded) spectrum's scale.
void DrawEstimates(cv::Mat& image, const Panel& spectrum, const LinkIdentification& link) {
  for (const SignalEstimate& e : link.estimates) {
    if (!e.dominant.has_frequency()) continue;
    const cv::Point a = spectrum.At(e.dominant.frequency_hz, spectrum.y0);
    cv::line(image, a, {a.x, spectrum.box.y}, EstimatorColour(e.estimator), 1, cv::LINE_AA);
    if (e.estimator == EstimatorKind::kHalfPowerFft && e.dominant.channel >= 0 &&
        e.dominant.channel < static_cast<int>(e.peaks.size())) {
      const SpectralPeak& p = e.peaks[e.dominant.channel];
      if (std::isfinite(p.left_hz) && std::isfinite(p.right_hz)) {
        const double level = p.peak_amplitude / std::sqrt(2.0) * kScale;
        cv::line(image, spectrum.At(p.left_hz, std::min(level, spectrum.y1)),
                 spectrum.At(p.right_hz, std::min(level, spectrum.y1)),
                 EstimatorColour(e.estimator), 2, cv::LINE_AA);
      }
    }
  }
}

// Bottom panel: both planes' amplitude spectra, zero-padded and with no window so the paper's
// peak shows as it saw it, and every estimator's frequency.
void DrawSpectrumPanel(cv::Mat& image, const LinkIdentification& link, const Panel& time,
                       const SpectrumPlotOptions& options) {
  const SampledSignal& s = link.deflection.signal;
  const double f_dom = link.value.has_frequency() ? link.value.frequency_hz : 1.0;
  const double nyquist = 0.5 / s.dt;
  const double f_max = options.max_frequency_hz > 0 ? options.max_frequency_hz
                                                    : std::min(nyquist, std::max(4.0, 3.0 * f_dom));
  Panel spectrum{
      cv::Rect(70, time.box.y + time.box.height + 70, options.width - 100, time.box.height), 0,
      f_max, 0, 0};
  const Eigen::MatrixXd filled = s.TrimInvalidEnds().FilledValues();
  std::vector<AmplitudeSpectrum> spectra;
  double top = 0;
  for (int c = 0; c < std::min(2, s.channels()); ++c) {
    SpectrumOptions so;
    so.zero_pad_factor = 8;
    spectra.push_back(ComputeAmplitudeSpectrum(
        std::vector<double>(filled.col(c).data(), filled.col(c).data() + filled.rows()), s.dt, so));
    for (int k = 1; k < spectra.back().size(); ++k) {
      if (spectra.back().frequency(k) <= f_max) {
        top = std::max(top, spectra.back().amplitude[k] * kScale);
      }
    }
  }
  spectrum.y1 = top > 0 ? 1.1 * top : 1.0;
  Axes(image, spectrum, "frequency (Hz)",
       fmt::format("amplitude spectrum ({}), zero-padded x8; lines: estimated f",
                   Unit(link.deflection)),
       f_max > 6 ? 1.0 : 0.5);
  for (size_t c = 0; c < spectra.size(); ++c) {
    std::vector<double> x(spectra[c].size()), y(spectra[c].size());
    for (int k = 0; k < spectra[c].size(); ++k) {
      x[k] = spectra[c].frequency(k);
      y[k] = spectra[c].amplitude[k] * kScale;
    }
    Polyline(image, spectrum, x, y, kChannel[c], 1);
  }
  DrawEstimates(image, spectrum, link);
}

}  // namespace

void SpectrumPlotOptions::Validate() const {
  CheckAtLeast("width", width, 300);
  CheckAtLeast("height", height, 300);
  CheckNonNegative("max_frequency_hz", max_frequency_hz);
}

void WriteLinkPlot(const IdentificationResult& result, const LinkIdentification& link,
                   const std::filesystem::path& path, const SpectrumPlotOptions& options) {
  options.Validate();
  cv::Mat image(options.height, options.width, CV_8UC3, kWhite);
  const int line = DrawHeader(image, result, link);
  if (link.deflection.signal.size() < 2) {
    const std::string& problem = link.deflection.problem;
    Text(image, problem.empty() ? "no signal" : problem, {20, line + 40}, 0.55);
  } else {
    DrawSpectrumPanel(image, link, DrawTimePanel(image, link, line, options), options);
  }
  std::vector<uchar> png;
  if (!cv::imencode(".png", image, png)) {
    throw IoError(fmt::format("{}: cannot encode the plot as PNG", path.string()));
  }
  WriteFileAtomically(path, std::string(png.begin(), png.end()));
}

std::string PlotFileName(const std::string& label) {
  std::string name = label;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return name + ".png";
}

void WriteLinkPlots(const IdentificationResult& result, const std::filesystem::path& folder,
                    const SpectrumPlotOptions& options) {
  AtomicDirectory out(folder);
  for (const LinkIdentification& link : result.links) {
    WriteLinkPlot(result, link, out.path() / PlotFileName(link.deflection.link.label), options);
  }
  out.Commit();
}

}  // namespace simtree::identification
