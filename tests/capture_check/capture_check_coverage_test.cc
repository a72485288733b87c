// The view coverage check registers the views (about 8 s on the quick capture): slow.

#include <filesystem>

#include <gtest/gtest.h>

#include "quick_capture.h"

namespace simtree::capture_check {
namespace {

TEST(CaptureCheckCoverage, TheQuickCaptureSurroundsItsTree) {
  const CaptureCheckResult r = CheckCapture(QuickCapture(), {});
  EXPECT_EQ(Find(r, "views registered", "scans").status, Status::kOk) << FormatTable(r);
  const Check gap = Find(r, "view coverage", "scans");
  EXPECT_EQ(gap.status, Status::kOk) << FormatTable(r);
  EXPECT_LT(gap.value, 120);
}

TEST(CaptureCheckCoverage, AMissingViewWarnsAndLeavesAGap) {
  const fs::path dir = CopyOfCapture();
  fs::remove_all(dir / "scans" / "view_02");
  const CaptureCheckResult r = CheckCapture(dir, {});
  const Check views = Find(r, "scan views", "scans");
  EXPECT_EQ(views.status, Status::kWarn);
  EXPECT_NE(views.message.find("3 views"), std::string::npos) << views.message;
  const Check gap = Find(r, "view coverage", "scans");
  EXPECT_EQ(gap.status, Status::kWarn) << FormatTable(r);
  EXPECT_GT(gap.value, 120);
}

}  // namespace
}  // namespace simtree::capture_check
