#pragma once
// The contact sheet of a synthetic capture: every view's colour image beside its false-colour
// depth, in a grid with labels, so a person can check at a glance that each view shows the tree.

#include <string>
#include <vector>

#include "simtree/io/depth_colormap.h"
#include "simtree/io/image_io.h"

namespace simtree::synth {

struct ContactSheetTile {
  std::string label;  // "view_03", "pull frame 120 (release)"
  RgbImage color;
  DepthImage depth;  // same size as `color`
};

struct ContactSheetOptions {
  int columns = 2;     // tiles per row (a tile is colour and depth side by side)
  double scale = 0.5;  // of each image
  DepthColormapOptions depth;
};

// Throws InputError when a tile's colour and depth sizes differ or there are no tiles.
RgbImage MakeContactSheet(const std::vector<ContactSheetTile>& tiles,
                          const ContactSheetOptions& options = {});

}  // namespace simtree::synth
