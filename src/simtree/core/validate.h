#pragma once
// Checks that a Tree is well formed before any stage trusts it.

#include <string>
#include <vector>

#include "simtree/core/tree.h"

namespace simtree {

struct ValidationOptions {
  // How far a child's first node may be from its parent's attachment node (metres).
  double attachment_tolerance_m = 1e-3;
  // Physical ranges of modal material values.
  double min_frequency_hz = 0.01;
  double max_frequency_hz = 200.0;
  double max_damping_ratio = 1.0;
  // Require a material on every branch (a simulation-ready tree).
  bool require_materials = false;
};

struct ValidationProblem {
  std::string where;    // "branches[3].nodes[0].radius"
  std::string message;  // "expected a positive radius, got -0.1"
};

// Every problem found, in branch order (empty when the tree is valid).
std::vector<ValidationProblem> FindProblems(const Tree& tree,
                                            const ValidationOptions& options = {});

// Throws InputError naming `source` and the first problem (and how many more there are).
void Validate(const Tree& tree, const std::string& source, const ValidationOptions& options = {});

}  // namespace simtree
