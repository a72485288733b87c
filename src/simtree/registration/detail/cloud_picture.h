#pragma once
// Point clouds drawn as a picture a person can check: orthographic views (from the side and from
// above, in a Z-up frame) of several clouds, each in its own colour, nearer points over farther
// ones. Used for the before/after picture of `simtree register`.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/image_io.h"

namespace simtree::registration {

struct PictureLayer {
  const std::vector<Eigen::Vector3d>* points = nullptr;  // Z-up frame
  std::array<uint8_t, 3> color = {0, 0, 0};
  int dot_px = 1;  // square dot size
};

struct PicturePanel {
  std::string title;
  std::vector<PictureLayer> layers;
};

struct PictureOptions {
  int panel_width = 560;  // px, >= 64: each panel is a side view over a top view
  int side_height = 560;  // px, >= 64
  int top_height = 420;   // px, >= 64
  // The side view looks along this horizontal direction (unit, z = 0; z is dropped).
  Eigen::Vector3d side_direction = Eigen::Vector3d::UnitY();
  // Share the scale and centre of all panels (the last panel's bounds), so they compare.
  bool common_scale = true;
  // A band under the panels naming the colours.
  std::vector<std::pair<std::string, std::array<uint8_t, 3>>> legend;

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// Distinct colours for up to 12 views (then they repeat).
std::array<uint8_t, 3> ViewColor(int index);

// Panels side by side: each a side view (x across, z up) over a top view (x across, y up), with
// its title above. Throws InputError when there are no panels.
RgbImage DrawPanels(const std::vector<PicturePanel>& panels, const PictureOptions& options = {});

}  // namespace simtree::registration
