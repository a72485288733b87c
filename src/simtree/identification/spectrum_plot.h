#pragma once
// A picture per link for a person to check an identification: the deflection signal of both
// planes with the fitted model over it (top), their amplitude spectra with every estimator's
// frequency and the paper's half-power band (bottom), and the values as text. PNG via OpenCV.

#include <filesystem>
#include <string>

#include "simtree/identification/identify.h"

namespace simtree::identification {

struct SpectrumPlotOptions {
  int width = 1100;  // px, >= 300
  int height = 760;  // px, >= 300
  // Highest frequency shown, Hz; 0: three times the dominant frequency, at least 4 Hz.
  double max_frequency_hz = 0.0;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// Writes `path` (PNG) for one link. A link without a signal (missing marker) gets a plot that
// says so. Throws IoError when the file cannot be written.
void WriteLinkPlot(const IdentificationResult& result, const LinkIdentification& link,
                   const std::filesystem::path& path, const SpectrumPlotOptions& options = {});

// The file name of a link's plot: its label with anything but letters, digits, '-' and '_'
// replaced by '_', and ".png".
std::string PlotFileName(const std::string& label);

// One plot per link in `folder` (PlotFileName), written whole or not at all.
void WriteLinkPlots(const IdentificationResult& result, const std::filesystem::path& folder,
                    const SpectrumPlotOptions& options = {});

}  // namespace simtree::identification
