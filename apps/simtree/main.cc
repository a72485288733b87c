// simtree: one RGB-D camera to a simulation-ready tree. The CLI is thin: each verb parses its
// options and calls the library.

#include <cstdio>
#include <memory>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <CLI/CLI.hpp>

#include "simtree/core/error.h"
#include "simtree/core/interrupt.h"
#include "simtree/core/log.h"
#include "simtree/core/progress.h"
#include "verbs.h"

#ifndef SIMTREE_VERSION
#define SIMTREE_VERSION "unknown"
#endif

int main(int argc, char** argv) {
  // Ctrl-C stops long work at its next step with nothing half-written (core/interrupt.h).
  simtree::InstallInterruptHandlers();
  CLI::App app{
      "simtree: a real tree from one consumer RGB-D camera, as a simulation-ready tree "
      "(branch hierarchy of generalized cylinders with measured natural frequencies and damping "
      "ratios).\n\n"
      "Pipeline: capture-from (Azure .mkv, RealSense .bag, TUM, Open3D) | synth -> capture folder\n"
      "          capture-check: what to fix in a capture before the run\n"
      "          scans -> preprocess -> register -> reconstruct -> static tree\n"
      "          pull-test stream -> track -> identify -> materials\n"
      "          static tree + materials -> build -> simulate / view / render / export\n"
      "          run: all of it on a capture folder; demo: synth + run + eval",
      "simtree"};
  app.set_version_flag("--version", std::string("simtree ") + SIMTREE_VERSION);
  std::string log_level = "info";
  int threads = 0;
  bool quiet = false;
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->capture_default_str();
  app.add_option("--threads", threads, "Worker threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", quiet, "No progress display");
  app.require_subcommand(1);
  app.fallthrough();

  using namespace simtree::cli;
  RegisterCaptureFrom(app);
  RegisterCaptureExport(app);
  RegisterCaptureCheck(app);
  RegisterSynth(app);
  RegisterPreprocess(app);
  RegisterRegister(app);
  RegisterReconstruct(app);
  RegisterTrack(app);
  RegisterIdentify(app);
  RegisterBuild(app);
  RegisterSimulate(app);
  RegisterExport(app);
  RegisterView(app);
  RegisterRender(app);
  RegisterRun(app);
  RegisterDemo(app);
  RegisterEval(app);
  RegisterReport(app);
  RegisterConvert(app);
  RegisterMesh(app);
  RegisterInfo(app);

  std::unique_ptr<oneapi::tbb::global_control> thread_limit;
  app.parse_complete_callback([&] {
    simtree::ConfigureLogging(log_level);
    simtree::Progress::SetEnabled(!quiet);
    if (threads > 0) {
      thread_limit = std::make_unique<oneapi::tbb::global_control>(
          oneapi::tbb::global_control::max_allowed_parallelism, threads);
    }
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const simtree::Interrupted& e) {
    std::fprintf(stderr, "simtree: %s\n", e.what());
    return e.exit_code();
  } catch (const simtree::Error& e) {
    std::fprintf(stderr, "simtree: error: %s\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "simtree: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
