#include "simtree/core/atomic_file.h"

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

TEST(AtomicFile, NothingAppearsUntilCommit) {
  const auto dir = test::TempDir();
  {
    AtomicFile f(dir / "out.txt");
    f.stream() << "hello";
    EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
    f.Commit();
  }
  EXPECT_EQ(test::ReadText(dir / "out.txt"), "hello");
  {
    AtomicFile f(dir / "out.txt");
    f.stream() << "half written";
    // No commit: an exception on the way out.
  }
  EXPECT_EQ(test::ReadText(dir / "out.txt"), "hello");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(AtomicDirectory, ReplacesTheOldFolderOnlyOnCommit) {
  const auto dir = test::TempDir();
  {
    AtomicDirectory out(dir / "run");
    test::WriteText(out.path() / "a.txt", "1");
    out.Commit();
  }
  {
    AtomicDirectory out(dir / "run");
    test::WriteText(out.path() / "b.txt", "2");
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "a.txt"));
  {
    AtomicDirectory out(dir / "run/");
    test::WriteText(out.path() / "b.txt", "2");
    out.Commit();
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "run" / "a.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "b.txt"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
}

TEST(RefuseToOverwriteInputs, SameFileOrFolderAroundIt) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "in.json", "{}");
  EXPECT_THROW(RefuseToOverwriteInputs(dir / "in.json", {dir / "in.json"}), InputError);
  EXPECT_THROW(RefuseToOverwriteInputs(dir / "./sub/../in.json", {dir / "in.json"}), InputError);
  EXPECT_THROW(RefuseToOverwriteInputs(dir, {dir / "in.json"}), InputError);
  EXPECT_NO_THROW(RefuseToOverwriteInputs(dir / "out.json", {dir / "in.json"}));
  EXPECT_NO_THROW(RefuseToOverwriteInputs(dir / "in", {dir / "in.json"}));
}

TEST(ReadFile, MissingFileSaysSo) {
  try {
    ReadFile("/nonexistent/x.json");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/x.json: cannot open (no such file)");
  }
}

}  // namespace
}  // namespace simtree
