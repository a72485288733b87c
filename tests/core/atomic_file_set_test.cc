#include "simtree/core/atomic_file_set.h"

#include <iterator>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

long FilesIn(const fs::path& dir) { return std::distance(fs::directory_iterator(dir), {}); }

TEST(AtomicFileSet, EveryFileAppearsOnCommitWithItsExtension) {
  const auto dir = test::TempDir();
  AtomicFileSet set;
  const fs::path tree = set.Stage(dir / "tree.json");
  const fs::path mesh = set.Stage(dir / "sub" / "tree.ply");  // its folder is made
  EXPECT_EQ(tree.extension(), ".json");
  EXPECT_EQ(mesh.parent_path(), dir / "sub");
  test::WriteText(tree, "tree");
  test::WriteText(mesh, "mesh");
  EXPECT_FALSE(fs::exists(dir / "tree.json"));
  set.Commit();
  EXPECT_EQ(test::ReadText(dir / "tree.json"), "tree");
  EXPECT_EQ(test::ReadText(dir / "sub" / "tree.ply"), "mesh");
  EXPECT_EQ(FilesIn(dir), 2);  // tree.json and sub/
  EXPECT_EQ(FilesIn(dir / "sub"), 1);
}

TEST(AtomicFileSet, AFileNeverWrittenCommitsNone) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "a.txt", "older a");
  {
    AtomicFileSet set;
    test::WriteText(set.Stage(dir / "a.txt"), "new a");
    set.Stage(dir / "b.txt");  // its writer failed
    EXPECT_THAT(test::ErrorOf([&] { set.Commit(); }), HasSubstr("b.txt: was not written"));
  }
  EXPECT_EQ(test::ReadText(dir / "a.txt"), "older a");
  EXPECT_EQ(FilesIn(dir), 1);  // no temporary left
}

TEST(AtomicFileSet, WithoutCommitTheTargetsStayAsTheyWere) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "a.txt", "older a");
  {
    AtomicFileSet set;
    test::WriteText(set.Stage(dir / "a.txt"), "new a");
    test::WriteText(set.Stage(dir / "b.txt"), "new b");
    // An exception on the way out.
  }
  EXPECT_EQ(test::ReadText(dir / "a.txt"), "older a");
  EXPECT_EQ(FilesIn(dir), 1);
}

TEST(AtomicFileSet, AFolderIsRefusedWhenStaged) {
  const auto dir = test::TempDir();
  fs::create_directories(dir / "picture.png");
  AtomicFileSet set;
  EXPECT_THAT(test::ErrorOf<IoError>([&] { set.Stage(dir / "picture.png"); }),
              HasSubstr("picture.png: is a folder; expected a file to write"));
}

}  // namespace
}  // namespace simtree
