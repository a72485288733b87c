#include "simtree/pipeline/manifest.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/json_util.h"

#ifndef SIMTREE_VERSION
#define SIMTREE_VERSION "unknown"
#endif

namespace fs = std::filesystem;

namespace simtree::pipeline {

const StageRecord* Manifest::Find(const std::string& name) const {
  for (const StageRecord& s : stages) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string SimtreeVersion() { return SIMTREE_VERSION; }

nlohmann::ordered_json ManifestToJson(const Manifest& manifest) {
  nlohmann::ordered_json doc;
  doc["format"] = kRunFormat;
  doc["version"] = kRunFormatVersion;
  doc["simtree"] = manifest.simtree_version;
  doc["capture"] = manifest.capture;
  doc["options"] = manifest.options;
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  for (const StageRecord& s : manifest.stages) {
    stages.push_back({{"name", s.name},
                      {"status", s.status},
                      {"reused", s.reused},
                      {"wall_s", s.wall_s},
                      {"summary", s.summary},
                      {"error", s.error},
                      {"inputs", s.inputs},
                      {"outputs", s.outputs},
                      {"input_fingerprint", s.input_fingerprint},
                      {"output_fingerprint", s.output_fingerprint}});
  }
  doc["stages"] = stages;
  return doc;
}

namespace {

std::vector<std::string> Strings(const JsonNode& node, const std::string& key) {
  std::vector<std::string> out;
  if (!node.Has(key)) return out;
  for (const JsonNode& item : node.Field(key).ExpectArray().Items()) out.push_back(item.String());
  return out;
}

std::string OptionalString(const JsonNode& node, const std::string& key) {
  const std::optional<JsonNode> value = node.Find(key);
  return value ? value->String() : std::string();
}

StageRecord StageFromJson(const JsonNode& s) {
  s.ExpectObject();
  StageRecord r;
  r.name = s.String("name");
  r.status = s.String("status");
  if (r.status != "done" && r.status != "failed" && r.status != "interrupted" &&
      r.status != "not run") {
    s.FailAt(Member(s.at(), "status"),
             fmt::format("expected done, failed, interrupted or not run, got \"{}\"", r.status));
  }
  if (const auto reused = s.Find("reused")) r.reused = reused->Bool();
  if (const auto wall = s.Find("wall_s")) r.wall_s = wall->Number();
  r.summary = OptionalString(s, "summary");
  r.error = OptionalString(s, "error");
  r.inputs = Strings(s, "inputs");
  r.outputs = Strings(s, "outputs");
  r.input_fingerprint = OptionalString(s, "input_fingerprint");
  r.output_fingerprint = OptionalString(s, "output_fingerprint");
  return r;
}

}  // namespace

Manifest ManifestFromJson(const nlohmann::json& value, const std::string& source) {
  const JsonNode doc(value, source);
  doc.ExpectObject();
  CheckFormat(doc, kRunFormat, kRunFormatVersion);
  Manifest m;
  m.simtree_version = OptionalString(doc, "simtree");
  m.capture = OptionalString(doc, "capture");
  if (const auto options = doc.Find("options")) {
    m.options = nlohmann::ordered_json(options->ExpectObject().json());
  }
  for (const JsonNode& s : doc.Field("stages").ExpectArray().Items()) {
    m.stages.push_back(StageFromJson(s));
  }
  return m;
}

Manifest ReadManifest(const fs::path& path) {
  const JsonDocument doc = ReadJsonDocument(path);
  return ManifestFromJson(doc.value, doc.source);
}

void WriteManifest(const Manifest& manifest, const fs::path& path) {
  WriteFileAtomically(path, ManifestToJson(manifest).dump(1) + "\n");
}

void Fingerprint::AddBytes(const char* data, size_t size) {
  constexpr uint64_t kPrime = 1099511628211ull;
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t word;
    std::memcpy(&word, data + i, 8);
    hash_ = (hash_ ^ word) * kPrime;
    hash_ ^= hash_ >> 29;
  }
  for (; i < size; ++i) hash_ = (hash_ ^ static_cast<unsigned char>(data[i])) * kPrime;
  hash_ = (hash_ ^ size) * kPrime;
}

void Fingerprint::Add(const std::string& bytes) { AddBytes(bytes.data(), bytes.size()); }

void Fingerprint::AddFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot be read for its fingerprint");
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const std::streamsize got = in.gcount();
    if (got > 0) AddBytes(buffer.data(), static_cast<size_t>(got));
  }
}

void Fingerprint::AddTree(const fs::path& path) {
  if (!fs::exists(path)) {
    Add("<missing>");
    return;
  }
  if (!fs::is_directory(path)) {
    AddFile(path);
    return;
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(path)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    Add(file.lexically_relative(path).generic_string());
    AddFile(file);
  }
}

std::string Fingerprint::Hex() const { return fmt::format("{:016x}", hash_); }

std::string FingerprintPaths(const std::vector<fs::path>& paths, const std::string& salt) {
  Fingerprint f;
  f.Add(salt);
  for (const fs::path& p : paths) f.AddTree(p);
  return f.Hex();
}

std::string OutputFingerprint(const std::vector<std::string>& outputs, const fs::path& result_dir) {
  std::vector<fs::path> paths;
  for (const std::string& o : outputs) paths.push_back(result_dir / o);
  return FingerprintPaths(paths);
}

std::string RerunReason(const StageRecord* previous, const std::string& input_fingerprint,
                        const fs::path& result_dir) {
  if (!previous) return "not in run.json";
  if (previous->status != "done") return "was " + previous->status;
  if (previous->input_fingerprint != input_fingerprint) return "its inputs or options changed";
  for (const std::string& o : previous->outputs) {
    if (!fs::exists(result_dir / o)) return o + " is missing";
  }
  if (OutputFingerprint(previous->outputs, result_dir) != previous->output_fingerprint) {
    return "its outputs changed";
  }
  return "";
}

}  // namespace simtree::pipeline
