#pragma once
// Medial samples of a scan: the points cut into bands of equal geodesic distance from the base,
// each connected piece of a band replaced by its centroid. A band crosses a branch like a ring,
// so the centroid lies near the branch axis whatever the branch's thickness; this is what lets
// space colonization, which grows through its attraction points, follow a 20 cm trunk and a 1 cm
// twig with the same few-centimetre step.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/scan_graph.h"

namespace simtree::reconstruction {

struct GeodesicSampleOptions {
  double band_width_m = 0.02;  // metres, the geodesic width of a band
  int min_points = 1;          // points a piece needs; smaller pieces are dropped as outliers
  // Pieces of one band whose centroids are closer than this times the sum of their spreads are
  // one piece: the arcs a ring breaks into where part of a branch was hidden, or where the band
  // crosses a leaning branch obliquely. 0 turns merging off.
  double merge_per_spread = 0.9;

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct GeodesicSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // centroid of the piece
  double geodesic_m = 0.0;  // mean geodesic distance of the piece's points
  int band = 0;
  int parent = -1;  // the sample its nearest-to-base point was reached from; -1 at the base
  int points = 0;
  double spread_m = 0.0;  // RMS distance of the piece's points from their centroid
};

struct GeodesicSampling {
  std::vector<GeodesicSample> samples;
  std::vector<int> sample_of_point;  // per point; -1 when unreached or dropped
  size_t unreached_points = 0;       // no path from the base (not bridged)
  size_t dropped_points = 0;         // in pieces smaller than min_points
  int merged_pieces = 0;             // arcs merged into rings
};

GeodesicSampling SampleGeodesicBands(std::span<const Eigen::Vector3d> points,
                                     const ScanGraph& graph, const GeodesicField& field,
                                     const GeodesicSampleOptions& options);

}  // namespace simtree::reconstruction
