// `simtree report` as a user meets it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "report/report_fixtures.h"
#include "test_util.h"

namespace simtree::report {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

TEST(ReportCli, WritesTheReportOfAResultFolder) {
  const fs::path dir = test::TempDir();
  test::WriteResultFolder(dir / "result");
  const auto r = test::RunCli("-q report " + (dir / "result").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("wrote " + (dir / "result" / "report.html").string()));
  const std::string html = test::ReadText(dir / "result" / "report.html");
  EXPECT_THAT(html, HasSubstr("id=\"viewer-canvas\""));
  // Elsewhere, and smaller.
  const auto small = test::RunCli("-q report " + (dir / "result").string() + " --out " +
                                  (dir / "small.html").string() + " --max-mb 2 --render-frames 1");
  ASSERT_EQ(small.exit_code, 0) << small.output;
  EXPECT_LE(fs::file_size(dir / "small.html"), 2'000'000u);
}

TEST(ReportCli, SaysWhatIsWrong) {
  const fs::path dir = test::TempDir();
  auto r = test::RunCli("-q report " + (dir / "missing").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("missing"));
  r = test::RunCli("-q report " + dir.string() + " --javascript-dir " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("install the Debian package libjs-three"));
  EXPECT_FALSE(fs::exists(dir / "report.html"));
}

}  // namespace
}  // namespace simtree::report
