// `simtree capture-check` on bad input: a clear error and a non-zero exit (the checks themselves:
// tests/capture_check/).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

TEST(CaptureCheckCli, BadInputIsAClearError) {
  const fs::path dir = test::TempDir();
  test::CliResult r = test::RunCli("capture-check \"" + (dir / "nowhere").string() + "\"");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("nowhere: no such folder"), std::string::npos) << r.output;

  fs::create_directories(dir / "empty");
  r = test::RunCli("capture-check \"" + (dir / "empty").string() + "\"");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("not a capture folder: no capture.json, scans/ or pull/"),
            std::string::npos)
      << r.output;

  r = test::RunCli("capture-check");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("expected a capture folder, scan recordings or --pull"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace simtree
