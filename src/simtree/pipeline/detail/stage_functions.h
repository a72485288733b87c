#pragma once
// The work of each stage of `simtree run` (stage.h's table calls these). Each reads its inputs
// from the capture and the result folder, writes into StageContext::out_dir and returns its
// one-line summary; each throws an simtree::Error saying what went wrong.

#include <string>

#include "simtree/pipeline/stage.h"

namespace simtree::pipeline::detail {

std::string RunPreprocessStage(const StageContext& context);
std::string RunRegisterStage(const StageContext& context);
std::string RunReconstructStage(const StageContext& context);
std::string RunTrackStage(const StageContext& context);
std::string RunIdentifyStage(const StageContext& context);
std::string RunBuildStage(const StageContext& context);
std::string RunSimulateStage(const StageContext& context);
std::string RunRenderStage(const StageContext& context);
std::string RunReportStage(const StageContext& context);

}  // namespace simtree::pipeline::detail
