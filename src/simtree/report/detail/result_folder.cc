#include "simtree/report/detail/result_folder.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace fs = std::filesystem;

namespace simtree::report {
namespace {

// The capture folder as run.json names it: absolute, else relative to the working folder, the
// result folder or the folder holding it.
fs::path FindCapture(const std::string& named, const fs::path& root) {
  if (named.empty()) return {};
  const fs::path p = named;
  std::vector<fs::path> candidates = {p};
  if (p.is_relative()) {
    candidates.push_back(root / p);
    candidates.push_back(root.parent_path() / p);
  }
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (fs::is_directory(c, ec)) return c;
  }
  return {};
}

}  // namespace

bool ResultFolder::HasFile(std::string_view relative) const {
  std::error_code ec;
  return fs::is_regular_file(root / relative, ec);
}

bool ResultFolder::HasFolder(std::string_view relative) const {
  std::error_code ec;
  return fs::is_directory(root / relative, ec);
}

std::vector<fs::path> ResultFolder::Files(std::string_view folder,
                                          const std::vector<std::string>& extensions) const {
  std::vector<fs::path> files;
  if (!HasFolder(folder)) return files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root / folder, ec)) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

const StageRecord* ResultFolder::Stage(std::string_view name) const {
  if (!run) return nullptr;
  for (const StageRecord& s : run->stages) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::optional<JsonNode> FindValue(const JsonNode& node, const std::string& key) {
  std::optional<JsonNode> found = node.Find(key);
  if (found && found->is_null()) return std::nullopt;
  return found;
}

fs::path ResultFolder::TrajectoriesFile() const {
  if (HasFile("track/trajectories.csv")) return Path("track/trajectories.csv");
  if (!HasFile("identify/materials.json")) return {};
  try {
    const JsonDocument doc = ReadJsonDocument(Path("identify/materials.json"));
    const auto record = FindValue(doc.root(), "record");
    const auto named = record ? FindValue(*record, "trajectories") : std::nullopt;
    if (!named || !named->json().is_string()) return {};
    const fs::path p = named->String();
    for (const fs::path& c : {p, root / p, root.parent_path() / p, root / "identify" / p}) {
      std::error_code ec;
      if (fs::is_regular_file(c, ec)) return c;
    }
  } catch (const Error&) {
  }
  return {};
}

std::vector<int> EvenlySpread(int total, int count) {
  std::vector<int> picked;
  if (total <= 0 || count <= 0) return picked;
  if (count >= total) {
    for (int i = 0; i < total; ++i) picked.push_back(i);
    return picked;
  }
  for (int k = 0; k < count; ++k) {
    const int i = count == 1 ? 0 : static_cast<int>(std::lround(k * (total - 1.0) / (count - 1)));
    if (picked.empty() || picked.back() != i) picked.push_back(i);
  }
  return picked;
}

RunManifest ParseRunManifest(const std::string& text, const std::string& source) {
  RunManifest run;
  run.document = ParseJson(text, source);
  const JsonNode doc(run.document, source);
  doc.ExpectObject();
  CheckFormat(doc, "simtree.run", 1);
  if (auto v = FindValue(doc, "simtree")) run.simtree_version = v->String();
  if (auto c = FindValue(doc, "capture")) run.capture = c->String();
  if (auto stages = FindValue(doc, "stages")) {
    for (const JsonNode& s : stages->Items()) {
      StageRecord r;
      r.name = s.String("name");
      if (auto v = FindValue(s, "status")) r.status = v->String();
      if (auto v = FindValue(s, "wall_s")) r.wall_s = v->Number();
      if (auto v = FindValue(s, "summary")) r.summary = v->String();
      if (auto v = FindValue(s, "outputs")) {
        for (const JsonNode& o : v->Items()) {
          r.outputs.push_back(o.json().is_string() ? o.String() : o.json().dump());
        }
      }
      run.stages.push_back(std::move(r));
    }
  }
  return run;
}

ResultFolder OpenResultFolder(const fs::path& root) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) {
    throw InputError(root.string(), "", "expected a result folder (what `simtree run` writes)");
  }
  ResultFolder folder;
  folder.root = root;
  if (folder.HasFile("run.json")) {
    try {
      const fs::path path = root / "run.json";
      folder.run = ParseRunManifest(ReadFile(path), path.string());
      folder.capture = FindCapture(folder.run->capture, root);
    } catch (const Error& e) {
      folder.run_problem = e.what();
    }
  }
  return folder;
}

}  // namespace simtree::report
