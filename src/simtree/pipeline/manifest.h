#pragma once
// run.json (`simtree.run` v1): what `simtree run` did, stage by stage, and the content
// fingerprints that decide whether a stage can be reused by the next run.
//
//   {"format": "simtree.run", "version": 1, "simtree": "0.1.0", "capture": "/abs/capture",
//    "options": {...},
//    "stages": [{"name": "preprocess", "status": "done", "reused": false, "wall_s": 3.2,
//                "summary": "4 of 4 views usable", "error": "", "inputs": ["capture/scans"],
//                "outputs": ["preprocess"], "input_fingerprint": "9f0c...",
//                "output_fingerprint": "41aa..."}, ...]}
//
// status: "done", "failed", "interrupted" (Ctrl-C) or "not run". A fingerprint is 16 hex digits
// of a 64-bit hash over the files' relative paths and bytes (a folder: every file under it, in name
// order).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/core/error.h"

namespace simtree::pipeline {

inline constexpr const char* kRunFormat = "simtree.run";
inline constexpr int kRunFormatVersion = 1;

// A stage that failed: the message starts with the stage's name.
class StageError : public Error {
 public:
  StageError(const std::string& stage, const std::string& message)
      : Error("stage " + stage + " failed: " + message), stage_(stage) {}
  const std::string& stage() const { return stage_; }

 private:
  std::string stage_;
};

struct StageRecord {
  std::string name;
  std::string status = "not run";  // "done", "failed", "interrupted", "not run"
  bool reused = false;             // done by an earlier run, its outputs kept
  double wall_s = 0.0;
  std::string summary;                       // one line
  std::string error;                         // why it failed
  std::vector<std::string> inputs, outputs;  // "capture/..." or relative to the result folder
  std::string input_fingerprint, output_fingerprint;
};

struct Manifest {
  std::string simtree_version;
  std::string capture;
  nlohmann::ordered_json options = nlohmann::ordered_json::object();
  std::vector<StageRecord> stages;

  const StageRecord* Find(const std::string& name) const;
};

// The version this library was built as.
std::string SimtreeVersion();

nlohmann::ordered_json ManifestToJson(const Manifest& manifest);
// Throws InputError naming `source` and the field.
Manifest ManifestFromJson(const nlohmann::json& doc, const std::string& source);
Manifest ReadManifest(const std::filesystem::path& path);
void WriteManifest(const Manifest& manifest, const std::filesystem::path& path);

// A streaming 64-bit hash (FNV-1a over 8-byte words), printed as 16 hex digits.
class Fingerprint {
 public:
  void Add(const std::string& bytes);
  void AddFile(const std::filesystem::path& path);
  // Every regular file under `path` (or the file itself): relative name, then bytes. A missing
  // path adds a marker of its absence.
  void AddTree(const std::filesystem::path& path);
  std::string Hex() const;

 private:
  void AddBytes(const char* data, size_t size);
  uint64_t hash_ = 14695981039346656037ull;
};

// The fingerprint of `paths` (each a file or a folder; missing ones count as missing).
std::string FingerprintPaths(const std::vector<std::filesystem::path>& paths,
                             const std::string& salt = "");

// The fingerprint of a stage's outputs (paths relative to `result_dir`).
std::string OutputFingerprint(const std::vector<std::string>& outputs,
                              const std::filesystem::path& result_dir);

// Why a stage must run again, or empty when `previous` (its record in the last run.json, null when
// none) lets it be reused: done before, with the same input fingerprint, and every output still
// there with the fingerprint recorded.
std::string RerunReason(const StageRecord* previous, const std::string& input_fingerprint,
                        const std::filesystem::path& result_dir);

}  // namespace simtree::pipeline
