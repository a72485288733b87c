#pragma once
// Helpers shared by the test suites: a fresh temporary folder per test, the shared data folder,
// running the CLI.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::test {

// ../shared/data (set by CMake). Fails the test loudly if the folder is not there.
inline std::filesystem::path SharedData(const std::string& relative = "") {
  const std::filesystem::path root = SIMTREE_SHARED_DATA_DIR;
  EXPECT_TRUE(std::filesystem::exists(root / relative))
      << "missing shared data " << (root / relative) << " (set -DSIMTREE_SHARED_DIR)";
  return root / relative;
}

// A folder unique to the running test, emptied when the test starts.
inline std::filesystem::path TempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(SIMTREE_TEST_TMP_DIR) /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The message of the exception of type E that `f` throws, or "" when it throws none.
template <typename E = Error, typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void WriteText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs `simtree <args>` (the binary built beside the tests) through the shell.
inline CliResult RunCli(const std::string& args) {
  const std::filesystem::path log =
      std::filesystem::path(SIMTREE_TEST_TMP_DIR) / ("cli-" + std::to_string(::getpid()) + ".log");
  std::filesystem::create_directories(log.parent_path());
  const std::string command =
      std::string("\"") + SIMTREE_CLI_PATH + "\" " + args + " > \"" + log.string() + "\" 2>&1";
  const int status = std::system(command.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.output = ReadText(log);
  std::filesystem::remove(log);
  return r;
}

}  // namespace simtree::test
