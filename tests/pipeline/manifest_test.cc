#include "simtree/pipeline/manifest.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace simtree::pipeline;

namespace {

Manifest Sample() {
  Manifest m;
  m.simtree_version = "0.1.0";
  m.capture = "/data/capture";
  m.options = {{"seed", 3}};
  StageRecord r;
  r.name = "preprocess";
  r.status = "done";
  r.reused = true;
  r.wall_s = 2.5;
  r.summary = "4 of 4 views usable";
  r.inputs = {"capture/scans"};
  r.outputs = {"preprocess"};
  r.input_fingerprint = "0123456789abcdef";
  r.output_fingerprint = "fedcba9876543210";
  m.stages.push_back(r);
  StageRecord failed;
  failed.name = "register";
  failed.status = "failed";
  failed.error = "no pairs";
  m.stages.push_back(failed);
  return m;
}

TEST(Manifest, RoundTripKeepsEveryField) {
  const fs::path dir = simtree::test::TempDir();
  const Manifest m = Sample();
  WriteManifest(m, dir / "run.json");
  const Manifest back = ReadManifest(dir / "run.json");
  EXPECT_EQ(back.simtree_version, "0.1.0");
  EXPECT_EQ(back.capture, "/data/capture");
  EXPECT_EQ(back.options["seed"], 3);
  ASSERT_EQ(back.stages.size(), 2u);
  const StageRecord& r = back.stages[0];
  EXPECT_EQ(r.name, "preprocess");
  EXPECT_EQ(r.status, "done");
  EXPECT_TRUE(r.reused);
  EXPECT_DOUBLE_EQ(r.wall_s, 2.5);
  EXPECT_EQ(r.summary, "4 of 4 views usable");
  EXPECT_EQ(r.inputs, std::vector<std::string>{"capture/scans"});
  EXPECT_EQ(r.outputs, std::vector<std::string>{"preprocess"});
  EXPECT_EQ(r.input_fingerprint, "0123456789abcdef");
  EXPECT_EQ(r.output_fingerprint, "fedcba9876543210");
  EXPECT_EQ(back.stages[1].status, "failed");
  EXPECT_EQ(back.stages[1].error, "no pairs");
  ASSERT_NE(back.Find("register"), nullptr);
  EXPECT_EQ(back.Find("simulate"), nullptr);
}

TEST(Manifest, RejectsAnUnknownStatusNamingTheField) {
  nlohmann::json doc = ManifestToJson(Sample());
  doc["stages"][1]["status"] = "maybe";
  try {
    ManifestFromJson(doc, "run.json");
    FAIL() << "expected an InputError";
  } catch (const simtree::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stages[1].status"), std::string::npos) << e.what();
  }
  doc = ManifestToJson(Sample());
  doc["format"] = "simtree.other";
  EXPECT_THROW(ManifestFromJson(doc, "run.json"), simtree::InputError);
}

TEST(Fingerprint, FollowsContentNamesAndAbsence) {
  const fs::path dir = simtree::test::TempDir();
  fs::create_directories(dir / "a" / "sub");
  simtree::test::WriteText(dir / "a" / "x.txt", "hello");
  simtree::test::WriteText(dir / "a" / "sub" / "y.txt", "world");
  const std::string first = FingerprintPaths({dir / "a"});
  EXPECT_EQ(first.size(), 16u);
  EXPECT_EQ(FingerprintPaths({dir / "a"}), first);
  simtree::test::WriteText(dir / "a" / "sub" / "y.txt", "World");
  const std::string edited = FingerprintPaths({dir / "a"});
  EXPECT_NE(edited, first);
  fs::rename(dir / "a" / "sub" / "y.txt", dir / "a" / "sub" / "z.txt");
  EXPECT_NE(FingerprintPaths({dir / "a"}), edited);
  EXPECT_NE(FingerprintPaths({dir / "missing"}), FingerprintPaths({dir / "a"}));
  EXPECT_NE(FingerprintPaths({dir / "a"}, "salt"), FingerprintPaths({dir / "a"}));
}

TEST(RerunReason, ReusesOnlyAMatchingCompleteStage) {
  const fs::path dir = simtree::test::TempDir();
  fs::create_directories(dir / "build");
  simtree::test::WriteText(dir / "build" / "simready.json", "{}");
  StageRecord r;
  r.name = "build";
  r.status = "done";
  r.outputs = {"build"};
  r.input_fingerprint = "in";
  r.output_fingerprint = OutputFingerprint(r.outputs, dir);
  EXPECT_EQ(RerunReason(&r, "in", dir), "");
  EXPECT_EQ(RerunReason(nullptr, "in", dir), "not in run.json");
  EXPECT_EQ(RerunReason(&r, "other", dir), "its inputs or options changed");
  simtree::test::WriteText(dir / "build" / "simready.json", "{ }");
  EXPECT_EQ(RerunReason(&r, "in", dir), "its outputs changed");
  fs::remove_all(dir / "build");
  EXPECT_EQ(RerunReason(&r, "in", dir), "build is missing");
  r.status = "failed";
  EXPECT_EQ(RerunReason(&r, "in", dir), "was failed");
}

}  // namespace
