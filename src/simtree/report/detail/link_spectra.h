#pragma once
// The amplitude spectra of the marker links, for the page's charts: the identification library
// turns the trajectories into each link's deflection signal over the free decay identify used
// (materials.json's release and window), and its FFT gives the spectrum, zero-padded as in
// identify's own plots. Nothing is estimated here: the frequencies marked are materials.json's.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/identification/materials_file.h"
#include "simtree/io/trajectories.h"

namespace simtree::report {

struct LinkSpectrum {
  std::string label;
  std::string status;                  // materials.json's status of the link
  std::string unit;                    // "rad" (relative angle) or "m" (the root's displacement)
  double frequency_hz = std::nan("");  // materials.json's values (NaN when not measured)
  double damping_ratio = std::nan("");
  double bin_hz = 0.0;                         // spacing of the kept bins
  std::vector<std::string> channel_names;      // the two bending planes
  std::vector<std::vector<double>> amplitude;  // per channel, from 0 Hz up to the shown maximum
  std::string problem;  // why there is no spectrum (a marker without a track, ...)
};

// One spectrum per link of `materials`, in its order; at most `max_bins` bins a channel.
// Throws what IdentifyMaterials throws (no marker of the links has a trajectory).
std::vector<LinkSpectrum> ComputeLinkSpectra(const Trajectories& trajectories,
                                             const identification::MaterialsFile& materials,
                                             int max_bins = 1500);

// The page's data for the spectra charts.
nlohmann::json SpectraJson(const std::vector<LinkSpectrum>& spectra);

}  // namespace simtree::report
