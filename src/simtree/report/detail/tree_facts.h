#pragma once
// A tree's summary (core/tree_summary.h) as a small two-column table, for the reconstruction and
// the branches sections.

#include <string>

#include "simtree/core/tree_summary.h"

namespace simtree::report {

std::string TreeFactsTable(const TreeSummary& summary);

}  // namespace simtree::report
