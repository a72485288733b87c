// Ctrl-C in the middle of a long verb: exit 130, a message, no half-written output, and an older
// output of the same name left as it was.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_util.h"

extern char** environ;

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// `simtree <args>` started in the background, its output to `log`.
pid_t Start(const std::vector<std::string>& args, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv{const_cast<char*>(SIMTREE_CLI_PATH)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, SIMTREE_CLI_PATH, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Names in `dir` that start with `prefix`.
std::vector<std::string> Entries(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0) out.push_back(name);
  }
  return out;
}

TEST(InterruptCli, CtrlCStopsSynthWithNothingHalfWritten) {
  const fs::path dir = test::TempDir();
  const fs::path out = dir / "capture";
  fs::create_directories(out);
  test::WriteText(out / "older.txt", "an earlier output");
  const pid_t pid = Start({"synth", "--quick", "--seed", "3", "--out", out.string()}, dir / "log");
  ASSERT_GT(pid, 0);
  // Wait until synth writes into its staging folder (.capture.partial-*), then press Ctrl-C.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (Entries(dir, ".capture.partial").empty() && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(Entries(dir, ".capture.partial").empty()) << test::ReadText(dir / "log");
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string log = test::ReadText(dir / "log");
  ASSERT_TRUE(WIFEXITED(status)) << "ended by a signal: " << log;
  EXPECT_EQ(WEXITSTATUS(status), 130) << log;
  EXPECT_THAT(log, HasSubstr("simtree: interrupted"));
  EXPECT_TRUE(Entries(dir, ".capture").empty()) << "a staging folder was left behind";
  EXPECT_EQ(test::ReadText(out / "older.txt"), "an earlier output");
  EXPECT_EQ(Entries(out, "").size(), 1u);
}

}  // namespace
}  // namespace simtree
