#pragma once
// The tape's colour model: a hue interval (an angle, so red's interval spans the wrap at 0/360
// degrees), a least saturation and a least brightness. Hue and saturation barely change when the
// tape is shaded or lit by the sun, so the model holds under both; brightness only rejects pixels
// too dark to have a hue. `Weight` grades a pixel from 0 (not tape) to 1 (all tape), so a pixel
// half covered by tape counts about half: what sub-pixel centres and band boxes are made from.
//
// Away from the hue centre the least saturation rises: a camera's white balance and MJPEG chroma
// smearing turn bark orange-red (hue 10-35 degrees from a red tape, saturation 0.3-0.6), while
// the tape's own pixels keep their hue within a few degrees or their saturation; a flat interval
// wide enough for shaded tape also took that bark, whose depth then moved the marker.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/image_io.h"

namespace simtree::tracking::detail {

struct TapeColorModel {
  double hue_deg = 0.0;             // centre of the hue interval (degrees, 0 = red)
  double hue_tolerance_deg = 22.0;  // half-width of the interval (degrees)
  double min_saturation = 0.45;     // (max - min) / max of R, G, B
  double full_saturation = 0.65;    // saturation from which a pixel counts as all tape
  double min_value = 28.0;          // max of R, G, B (0-255)
  double hue_core_deg = 8.0;        // within this of the centre min_saturation applies ...
  double edge_saturation = 0.75;    // ... rising linearly to this at hue_tolerance_deg
  // The interval and its cone shifted outwards by this on one side (`extra_side` +1: towards
  // larger hues, -1: smaller): where the init frame's tapes lie away from the bark (FitColorModel).
  double extra_hue_deg = 0.0;
  int extra_side = -1;

  // A pixel's hue distance from the centre as the interval sees it: on the extended side the
  // extension is taken off.
  double EffectiveHueDistance(double hue_deg) const;

  // The least saturation of a tape pixel `hue_distance_deg` from the centre.
  double MinSaturationAt(double hue_distance_deg) const;

  // True when the pixel is tape (hue inside the interval, saturated and bright enough).
  bool Contains(uint8_t r, uint8_t g, uint8_t b) const;
  // 0 (not tape) to 1 (all tape): saturation graded from 0.7 min_saturation to full_saturation,
  // hue graded over 10 degrees outside the interval.
  float Weight(uint8_t r, uint8_t g, uint8_t b) const;
  std::string Describe() const;
};

// Hue in degrees [0, 360), saturation [0, 1] and value [0, 255] of an RGB pixel.
void RgbToHsv(uint8_t r, uint8_t g, uint8_t b, float* hue_deg, float* saturation, float* value);
// Smallest angle between two hues (degrees, 0-180).
double HueDistance(double a_deg, double b_deg);

// The starting model for `--color`: "auto" and "red" are red; "green", "blue", "yellow",
// "orange" or "#rrggbb" set the hue. Throws InputError naming the option otherwise.
TapeColorModel ColorModelFromName(const std::string& name);

// Refits `prior` to the tape pixels (by the prior) around `pixels` (within `radius` px) of
// `image`: the hue centre becomes their circular median, the tolerance and thresholds follow their
// spread, never looser than the prior (the windows also hold bark, which may be reddish). Returns
// the prior unchanged when fewer than `min_samples` tape pixels are found. `samples_found`
// (optional) gets how many were used. Then the interval is extended on the side away from the
// background (ExtendAwayFromBackground).
TapeColorModel FitColorModel(const TapeColorModel& prior, const RgbImage& image,
                             const std::vector<Eigen::Vector2d>& pixels, int radius,
                             int min_samples = 12, int* samples_found = nullptr);

// A thin tape's colour mixes with what is beside it: MJPEG sends chroma at half the width, so a
// tape 2-4 px wide against sky reads 15-40 degrees from its hue towards blue (magenta for red)
// and dark (value 40-80): on synth's camera-colour streams 20% of the missed visible samples had
// no pixel of the model's colour at all, their most tape-like pixel at -30 to 0 degrees. Bark
// pulls the other way (orange), where the cone must stay. Per init pixel, the most saturated pixel
// within `radius` whose hue is within 60 degrees of the centre and that has the least saturation
// and value is taken as its tape; the background is the median signed hue of the frame's weakly
// saturated pixels (0.15 up to the least saturation) within those 60 degrees. The interval grows on
// the side opposite the background by the farthest such tape hue past the core (at most
// `max_extra_deg`); nothing when the tapes all fit.
TapeColorModel ExtendAwayFromBackground(const TapeColorModel& model, const RgbImage& image,
                                        const std::vector<Eigen::Vector2d>& pixels, int radius,
                                        double max_extra_deg = 30.0);

}  // namespace simtree::tracking::detail
