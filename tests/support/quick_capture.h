#pragma once
// One quick synthetic capture (synth --quick, seed 3, a 2 s pull just past the release at 1.8 s)
// shared by the tests of a suite, written once into the suite's temporary folder; and copies of it
// to spoil. Header-only: the suites that use it link simtree::synth themselves.

#include <filesystem>

#include "simtree/synth/synth.h"
#include "test_util.h"

namespace simtree::test {

inline const std::filesystem::path& QuickCapture() {
  static const std::filesystem::path root = [] {
    const std::filesystem::path dir = std::filesystem::path(SIMTREE_TEST_TMP_DIR) / "quick_capture";
    if (!std::filesystem::exists(dir / "capture.json")) {
      synth::SynthOptions options;
      options.quick = true;
      options.seed = 3;
      options.duration_s = 2.0;
      options.contact_sheet = false;
      synth::RunSynth(options, dir);
    }
    return dir;
  }();
  return root;
}

// A copy of the quick capture in the test's own temporary folder.
inline std::filesystem::path CopyOfQuickCapture() {
  const std::filesystem::path dir = TempDir() / "capture";
  std::filesystem::copy(QuickCapture(), dir, std::filesystem::copy_options::recursive);
  return dir;
}

}  // namespace simtree::test
