// Ctrl-C: the first signal only asks, and the work stops at its next progress step on the thread
// that made the Progress.

#include "simtree/core/interrupt.h"

#include <csignal>
#include <thread>

#include <gtest/gtest.h>

#include "simtree/core/progress.h"

namespace simtree {
namespace {

class InterruptTest : public ::testing::Test {
 protected:
  void SetUp() override { SetInterruptRequested(false); }
  void TearDown() override { SetInterruptRequested(false); }
};

TEST_F(InterruptTest, ProgressStopsTheOwningThreadOnce) {
  Progress::SetEnabled(false);
  Progress progress("work", 10, "items");
  progress.Advance();
  SetInterruptRequested(true);
  EXPECT_THROW(progress.Advance(), Interrupted);
  // Another thread's steps count but do not throw: it may be a plain worker thread, where an
  // exception would end the process.
  std::thread other([&] { EXPECT_NO_THROW(progress.Advance()); });
  other.join();
  Progress::SetEnabled(true);
}

TEST_F(InterruptTest, TheFirstSignalOnlyAsks) {
  InstallInterruptHandlers();
  EXPECT_FALSE(InterruptRequested());
  std::raise(SIGINT);  // would end the test binary without the handler
  EXPECT_TRUE(InterruptRequested());
  try {
    ThrowIfInterrupted();
    ADD_FAILURE() << "no Interrupted thrown";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.exit_code(), 130);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

}  // namespace
}  // namespace simtree
