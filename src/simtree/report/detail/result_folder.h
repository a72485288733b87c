#pragma once
// What the report reads: a result folder of `simtree run` (docs/report.md lists its files), and
// its manifest run.json. Every part may be missing; nothing here throws for a missing file.

#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/core/json_util.h"

namespace simtree::report {

// The stage folders in pipeline order (the names run.json uses).
inline constexpr const char* kStageNames[] = {"preprocess", "register", "reconstruct",
                                              "track",      "identify", "build",
                                              "simulate",   "render",   "eval"};

struct StageRecord {
  std::string name;
  std::string status;  // done, failed, skipped, not run (as run.json says)
  double wall_s = std::nan("");
  std::string summary;
  std::vector<std::string> outputs;
};

// run.json (`simtree.run` v1).
struct RunManifest {
  std::string simtree_version;
  std::string capture;  // as written
  std::vector<StageRecord> stages;
  nlohmann::json document;
};

struct ResultFolder {
  std::filesystem::path root;
  std::optional<RunManifest> run;  // when run.json exists and reads
  std::string run_problem;         // why run.json did not read (empty otherwise)
  std::filesystem::path capture;   // the capture folder run.json names, when it exists here

  std::filesystem::path Path(std::string_view relative) const { return root / relative; }
  bool HasFile(std::string_view relative) const;
  bool HasFolder(std::string_view relative) const;
  // Files of a folder with one of the extensions (".png"), sorted by name; empty when none.
  std::vector<std::filesystem::path> Files(std::string_view folder,
                                           const std::vector<std::string>& extensions) const;
  const StageRecord* Stage(std::string_view name) const;
  // The marker trajectories: track/trajectories.csv, else the file identify/materials.json says
  // it read (as written, or relative to the result folder or its parent); empty when neither.
  std::filesystem::path TrajectoriesFile() const;
};

// Up to `count` items of `total`, evenly spread and including the first and the last.
std::vector<int> EvenlySpread(int total, int count);

// The member `key` of `node` when it is there and not null (JsonNode::Find keeps a null): the
// report reads every optional member through this.
std::optional<JsonNode> FindValue(const JsonNode& node, const std::string& key);

// Parses run.json text (throws InputError naming `source` and the field).
RunManifest ParseRunManifest(const std::string& text, const std::string& source);

// Throws InputError when `root` is not a folder.
ResultFolder OpenResultFolder(const std::filesystem::path& root);

}  // namespace simtree::report
