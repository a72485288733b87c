#pragma once
// The page's own style sheet and script (the libraries are inlined beside them). The script reads
// the JSON data block (id "simtree-data"): charts for "trajectories" and "spectra", the 3D view
// for "animation"; it reports in the element "report-status" ("ok: ..." or "error: ..."), and
// window errors turn it to an error, which the end-to-end test reads.

#include <string_view>

namespace simtree::report {

std::string_view PageStyle();
std::string_view PageScript();

}  // namespace simtree::report
