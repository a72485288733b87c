#pragma once
// Every verb of the `simtree` CLI registers itself on the app. One file per verb; a verb holds no
// algorithm, only options, calls into the library and printing.

#include <CLI/CLI.hpp>

namespace simtree::cli {

void RegisterSynth(CLI::App& app);
void RegisterPreprocess(CLI::App& app);
void RegisterRegister(CLI::App& app);
void RegisterReconstruct(CLI::App& app);
void RegisterTrack(CLI::App& app);
void RegisterIdentify(CLI::App& app);
void RegisterBuild(CLI::App& app);
void RegisterSimulate(CLI::App& app);
void RegisterExport(CLI::App& app);  // robot simulators (verb_export.cc)
void RegisterView(CLI::App& app);
void RegisterRender(CLI::App& app);
void RegisterRun(CLI::App& app);
void RegisterEval(CLI::App& app);
void AddEvalRun(CLI::App& eval);  // `eval RESULT --gt CAPTURE` (verb_eval_run.cc)
void RegisterDemo(CLI::App& app);
void RegisterReport(CLI::App& app);
void RegisterConvert(CLI::App& app);
void RegisterMesh(CLI::App& app);
void RegisterInfo(CLI::App& app);
void RegisterCaptureFrom(CLI::App& app);
void RegisterCaptureExport(CLI::App& app);
void RegisterCaptureCheck(CLI::App& app);

}  // namespace simtree::cli
