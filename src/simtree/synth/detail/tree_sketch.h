#pragma once
// A quick picture of a tree to look at: three orthographic views side by side (front, looking
// along +Y; side, looking along -X; top, looking down -Z), branches drawn as shaded tubes of their
// true radius (at least one pixel wide), coloured by level (or bark), markers as red dots, a ground
// line and a 1 m scale bar. All three views share one scale, so sizes compare across them.

#include "simtree/core/tree.h"
#include "simtree/io/image_io.h"

namespace simtree::synth {

struct TreeSketchOptions {
  int view_height_px = 700;   // height of the front and side views (the top view is square)
  double margin_m = 0.15;     // space around the tree's bounds
  double min_width_px = 1.0;  // thinnest drawn branch
  bool draw_markers = true;
  bool colour_by_level = true;  // false: grey-brown bark, to judge the silhouette
};

RgbImage SketchTree(const Tree& tree, const TreeSketchOptions& options = {});

}  // namespace simtree::synth
