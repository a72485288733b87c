#pragma once
// A quick synthetic capture shared by the capture-check tests (written once per suite), copies of
// it to spoil, and finding a check in a result.

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "simtree/capture_check/capture_check.h"
#include "support/quick_capture.h"
#include "test_util.h"

namespace simtree::capture_check {

namespace fs = std::filesystem;

using test::QuickCapture;
inline fs::path CopyOfCapture() { return test::CopyOfQuickCapture(); }

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
