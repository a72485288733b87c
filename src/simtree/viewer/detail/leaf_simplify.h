#pragma once
// A leaf model with fewer triangles that looks the same at the size leaves are seen: hundreds of
// leaves a few tens of pixels long each, where the authors' ~150 triangles a leaf cost most of a
// software rasteriser's frame (docs/benchmarks.md, "Viewer and renderer").
//
//  - The blade: half-edge collapses (a vertex merged into a neighbour, so every kept vertex keeps
//    its position and texture coordinate), cheapest first, while every original vertex stays
//    within `tolerance` of the new triangles around it and the kept vertices within `tolerance`
//    of the planes of the faces they replace (which keeps folds such as the midrib). Boundary
//    vertices only slide along the boundary; no collapse flips a face or makes the mesh
//    non-manifold. The authors' apple blade goes from 99 to 22 triangles at 1 % of its length.
//  - The petiole: the polyline thinned by Douglas-Peucker with the same tolerance.

#include "simtree/viewer/detail/leaf_model.h"

namespace simtree::viewer {

struct LeafSimplifyOptions {
  // Largest distance the simplified surface and outline move, as a fraction of the leaf's length
  // (LeafModel::Length()). 0 keeps the model as it is.
  double tolerance = 0.01;
  // Blades with more vertices are kept as they are: the greedy search is quadratic, and a model
  // that large was made for close-ups.
  int max_blade_vertices = 1000;  // >= 0

  // Throws InputError ("leaf simplification", the field) for a value out of range.
  void Validate() const;
};

struct LeafSimplifyResult {
  LeafModel model;
  int blade_triangles_before = 0;
  int petiole_points_before = 0;
  double max_error = 0.0;  // the largest accepted collapse's or thinning's distance, leaf units
};

// Throws InputError for options out of range (options.Validate()). The model is assumed valid
// (as ParseLeafModel returns it).
LeafSimplifyResult SimplifyLeafModel(const LeafModel& model, const LeafSimplifyOptions& options);

}  // namespace simtree::viewer
