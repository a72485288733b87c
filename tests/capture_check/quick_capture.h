#pragma once
// A quick synthetic capture shared by the capture-check tests (written once per suite), copies of
// it to spoil, and finding a check in a result.

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "simtree/capture_check/capture_check.h"
#include "simtree/synth/synth.h"
#include "test_util.h"

namespace simtree::capture_check {

namespace fs = std::filesystem;

// One quick synthetic capture shared by the tests of this file (written once).
inline const fs::path& QuickCapture() {
  static const fs::path root = [] {
    const fs::path dir = fs::path(SIMTREE_TEST_TMP_DIR) / "quick_capture";
    if (!fs::exists(dir / "capture.json")) {
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

inline fs::path CopyOfCapture() {
  const fs::path dir = test::TempDir() / "capture";
  fs::copy(QuickCapture(), dir, fs::copy_options::recursive);
  return dir;
}

inline CaptureCheckOptions NoRegistration() {
  CaptureCheckOptions o;
  o.register_views = false;
  return o;
}

// The check `name` of `subject`; fails the test when absent.
inline Check Find(const CaptureCheckResult& r, const std::string& name,
                  const std::string& subject) {
  const auto it = std::find_if(r.checks.begin(), r.checks.end(), [&](const Check& c) {
    return c.name == name && c.subject == subject;
  });
  EXPECT_NE(it, r.checks.end()) << name << " of " << subject << "\n" << FormatTable(r);
  return it == r.checks.end() ? Check{} : *it;
}

}  // namespace simtree::capture_check
