#pragma once
// The paper's own demo format (shared/data/authors-demo): a tree_model/*.txt geometry file and a
// tree_parameters.txt material file. Read and written exactly, so a round trip gives the same
// bytes.
//
// Geometry, Y up, in the demo's own units:
//   RowMax=<branches>
//   <id> <node count> <child count> <colour word>          one block per branch
//   <child id> <node index on this branch>                 child count lines
//   <x> <y> <z> <radius>                                   node count lines, base to tip
// Parameters: a first line with the count, then one line "frequency_hz damping_ratio stiffness"
// per branch in id order.

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/core/tree.h"

namespace simtree {

struct LegacyOptions {
  // Metres per demo unit. The demo's trees are 15-16 units tall, so 0.25 makes them 3.7-4 m,
  // inside the paper's 2-5 m; a power of two keeps the conversion exact.
  double scale = 0.25;
  // The demo is Y-up; simtree is Z-up. (x, y, z)_demo -> (x, -z, y)_simtree.
  bool y_up = true;
};

// Reads a geometry file into a Tree with frames and levels (no materials). Branches are
// renumbered depth-first if the file lists a child before its parent.
Tree ReadLegacyTree(const std::filesystem::path& path, const LegacyOptions& options = {});

// Reads tree_parameters.txt and gives every branch of `tree` its material
// (all three modes at the line's frequency and damping; stiffness as given; source "default").
void ReadLegacyParameters(const std::filesystem::path& path, Tree& tree);

// The lines of a parameter file as the paper writes them, in branch order.
struct LegacyParameterLine {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double stiffness = 0.0;
};
std::vector<LegacyParameterLine> ParseLegacyParameters(const std::string& text,
                                                       const std::string& source);

// Writes atomically. The colour word is the demo's colour for the branch level.
void WriteLegacyTree(const Tree& tree, const std::filesystem::path& path,
                     const LegacyOptions& options = {});
// Needs a material on every branch; writes the first mode's frequency and damping and k.
void WriteLegacyParameters(const Tree& tree, const std::filesystem::path& path);

// The colour word the demo uses for a level (red trunk, green, blue, springgreen, ...).
std::string LegacyLevelColour(int level);

}  // namespace simtree
