#pragma once
// The sections of the page, one builder per section and file (section_<id>.cc). Each reads its
// stage's files through the stage's reader, says what is missing, and adds what its charts or
// viewer need to the page's data block.

#include <cstdint>

#include "simtree/report/detail/page_context.h"

namespace simtree::report {

Section BuildStagesSection(PageContext& page);          // run.json
Section BuildViewsSection(PageContext& page);           // preprocess/, the capture's views
Section BuildRegistrationSection(PageContext& page);    // register/
Section BuildReconstructionSection(PageContext& page);  // reconstruct/
Section BuildTrackingSection(PageContext& page);        // track/ (overlays, trajectories)
Section BuildIdentificationSection(PageContext& page);  // identify/ (spectra, ranges)
Section BuildBranchesSection(PageContext& page);        // build/simready.json
Section BuildRenderSection(PageContext& page);          // render/ (paper Fig. 15)
Section BuildPaperTablesSection(PageContext& page);     // the paper's tables beside this run's
Section BuildEvalSection(PageContext& page);            // eval/eval.json
// simulate/: the 3D view. Built last: its data gets `budget_bytes`, what the page leaves.
Section BuildAnimationSection(PageContext& page, int64_t budget_bytes, AnimationReport* report);

}  // namespace simtree::report
