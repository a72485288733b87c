#include "simtree/pipeline/run.h"

#include <algorithm>
#include <chrono>
#include <map>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/interrupt.h"
#include "simtree/core/progress.h"
#include "simtree/pipeline/stage.h"

namespace fs = std::filesystem;

namespace simtree::pipeline {
namespace {

int StageIndex(const std::string& name) {
  const auto& names = StageNames();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

bool Inside(const fs::path& path, const fs::path& folder) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(path, ec);
  const fs::path f = fs::weakly_canonical(folder, ec);
  const fs::path rel = p.lexically_relative(f);
  return !rel.empty() && rel.native().rfind("..", 0) != 0;
}

bool HasSubfolder(const fs::path& folder) {
  if (!fs::is_directory(folder)) return false;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.is_directory()) return true;
  }
  return false;
}

// The previous run.json, or an empty manifest (with a warning when it was there but unreadable).
Manifest PreviousManifest(const fs::path& path) {
  if (!fs::exists(path)) return {};
  try {
    return ReadManifest(path);
  } catch (const Error& e) {
    spdlog::warn("{}: cannot be read ({}); every stage runs again", path.string(), e.what());
    return {};
  }
}

// Fingerprints of the stages' inputs, each path hashed once per run.
class InputFingerprints {
 public:
  InputFingerprints(fs::path capture, fs::path result)
      : capture_(std::move(capture)), result_(std::move(result)) {}

  std::string Of(const Stage& stage, const RunOptions& options) {
    Fingerprint f;
    f.Add(stage.options(options).dump());
    for (const std::string& input : stage.inputs) {
      f.Add(input);
      f.Add(PathFingerprint(input));
    }
    return f.Hex();
  }

 private:
  std::string PathFingerprint(const std::string& input) {
    const bool in_capture = input.rfind("capture/", 0) == 0;
    const fs::path path = in_capture ? capture_ / input.substr(8) : result_ / input;
    // Capture files do not change during a run; result folders do (each stage writes one).
    if (in_capture) {
      auto it = cache_.find(input);
      if (it == cache_.end()) it = cache_.emplace(input, FingerprintPaths({path})).first;
      return it->second;
    }
    return FingerprintPaths({path});
  }

  fs::path capture_, result_;
  std::map<std::string, std::string> cache_;
};

// Runs one stage into its folder (written whole or not at all); returns its summary.
std::string RunStage(const Stage& stage, const StageContext& base) {
  if (!stage.folder) return stage.run(base);
  AtomicDirectory folder(base.result_dir / stage.name);
  StageContext context{base.capture, base.capture_dir, base.result_dir, base.options,
                       folder.path()};
  std::string summary = stage.run(context);
  folder.Commit();
  return summary;
}

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void RunOptions::Validate() const {
  const char* source = "run options";
  if (!from.empty() && StageIndex(from) >= static_cast<int>(StageNames().size())) {
    throw InputError(
        source, "from",
        fmt::format("expected a stage ({}), got \"{}\"", fmt::join(StageNames(), ", "), from));
  }
  if (!until.empty() && StageIndex(until) >= static_cast<int>(StageNames().size())) {
    throw InputError(
        source, "until",
        fmt::format("expected a stage ({}), got \"{}\"", fmt::join(StageNames(), ", "), until));
  }
  if (!from.empty() && !until.empty() && StageIndex(until) < StageIndex(from)) {
    throw InputError(source, "until",
                     fmt::format("expected a stage at or after --from {}, got {}", from, until));
  }
  if (held_out_markers < 0) {
    throw InputError(source, "held_out_markers",
                     fmt::format("expected a count >= 0, got {}", held_out_markers));
  }
  if (render_width < 16 || render_width > 8192) {
    throw InputError(source, "render_width",
                     fmt::format("expected 16 to 8192 pixels, got {}", render_width));
  }
}

nlohmann::ordered_json RunOptions::ToJson() const {
  return {{"tracks", tracks.empty() ? nlohmann::ordered_json(nullptr)
                                    : nlohmann::ordered_json(fs::absolute(tracks).string())},
          {"from", from},
          {"until", until},
          {"force", force},
          {"held_out_markers", held_out_markers},
          {"render", render},
          {"render_width", render_width},
          {"seed", seed}};
}

void CheckInputs(const fs::path& capture, const fs::path& result, const RunOptions& options) {
  if (!fs::is_directory(capture)) {
    throw InputError(capture.string(), "", "expected a capture folder (scans/, pull/)");
  }
  if (fs::exists(result) && !fs::is_directory(result)) {
    throw InputError(result.string(), "", "expected a folder for the result, found a file");
  }
  if (Inside(result, capture) || fs::weakly_canonical(result) == fs::weakly_canonical(capture)) {
    throw InputError(result.string(), "",
                     "refusing to write the result into the capture folder " + capture.string() +
                         "; choose another --out");
  }
  if (!HasSubfolder(capture / "scans")) {
    throw InputError(capture.string(), "scans/",
                     "expected the static scans (scans/view_00/, ...), found none");
  }
  if (!fs::is_regular_file(capture / "pull" / "frames.csv")) {
    throw InputError(capture.string(), "pull/frames.csv",
                     "expected the pull-test stream (pull/frames.csv and its frames), found none");
  }
  if (!fs::exists(capture / "pull" / "markers.json")) {
    throw InputError(capture.string(), "pull/markers.json",
                     "expected the tape markers and their links (simtree.markers), found none; "
                     "a capture made by `simtree capture-from` needs it written by hand "
                     "(docs/formats.md)");
  }
  if (!options.tracks.empty() && !fs::is_regular_file(options.tracks)) {
    throw InputError(options.tracks.string(), "", "expected a trajectories.csv file (--tracks)");
  }
  if (options.tracks.empty() && !fs::is_regular_file(capture / "pull" / "init.json")) {
    throw InputError(capture.string(), "pull/init.json",
                     "expected the markers' first-frame pixels to start tracking from "
                     "(simtree.track_init), found none (written by hand for a capture from "
                     "`simtree capture-from`, docs/formats.md); or give the trajectories with "
                     "--tracks");
  }
}

namespace {

// Whether a stage runs, and what its record says afterwards.
struct Runner {
  const std::vector<Stage>& table;
  const RunOptions& options;
  StageContext context;
  Manifest previous, now;
  InputFingerprints fingerprints;
  fs::path manifest_path;
  int first_forced = 0, last = 0;
  bool upstream_ran = false;
  RunResult result;

  // The stage's record in this run; throws StageError when it fails.
  void Do(int index) {
    const Stage& stage = table[index];
    StageRecord& record = now.stages[index];
    const StageRecord* old = previous.Find(stage.name);
    if (index > last) {
      if (old) record = *old;
      return;
    }
    if (stage.name == "render" && !options.render) {
      record.summary = "off (--no-render)";
      return;
    }
    const std::string input = fingerprints.Of(stage, options);
    std::string reason = options.force           ? "--force"
                         : index >= first_forced ? "--from " + options.from
                         : upstream_ran          ? "an earlier stage ran"
                                                 : RerunReason(old, input, context.result_dir);
    if (reason.empty()) {
      record = *old;
      record.reused = true;
      ++result.reused;
      spdlog::info("{}: unchanged, reused ({})", stage.name, record.summary);
      return;
    }
    spdlog::info("{}: running ({})", stage.name, reason);
    record.input_fingerprint = input;
    const auto start = std::chrono::steady_clock::now();
    try {
      record.summary = RunStage(stage, context);
    } catch (const Interrupted& e) {
      record.status = "interrupted";
      record.wall_s = Seconds(start);
      WriteManifest(now, manifest_path);
      throw;
    } catch (const std::exception& e) {
      record.status = "failed";
      record.wall_s = Seconds(start);
      record.error = e.what();
      WriteManifest(now, manifest_path);
      throw StageError(stage.name, e.what());
    }
    record.status = "done";
    record.wall_s = Seconds(start);
    record.output_fingerprint = OutputFingerprint(record.outputs, context.result_dir);
    upstream_ran = true;
    ++result.ran;
    spdlog::info("{}: done in {:.1f} s: {}", stage.name, record.wall_s, record.summary);
  }
};

Manifest FreshManifest(const fs::path& capture, const RunOptions& options) {
  Manifest m;
  m.simtree_version = SimtreeVersion();
  m.capture = fs::absolute(capture).lexically_normal().string();
  m.options = options.ToJson();
  for (const Stage& stage : StageTable()) {
    StageRecord r;
    r.name = stage.name;
    r.inputs = stage.inputs;
    r.outputs = stage.outputs;
    m.stages.push_back(r);
  }
  return m;
}

}  // namespace

RunResult Run(const fs::path& capture_dir, const fs::path& result_dir, const RunOptions& options) {
  options.Validate();
  CheckInputs(capture_dir, result_dir, options);
  const auto start = std::chrono::steady_clock::now();
  const Capture capture = OpenCapture(capture_dir);
  fs::create_directories(result_dir);
  const fs::path manifest_path = result_dir / "run.json";
  const std::vector<Stage>& table = StageTable();
  const int count = static_cast<int>(table.size());
  Runner runner{table,
                options,
                StageContext{capture, capture_dir, result_dir, options, result_dir},
                PreviousManifest(manifest_path),
                FreshManifest(capture_dir, options),
                InputFingerprints(capture_dir, result_dir),
                manifest_path,
                options.from.empty() ? count : StageIndex(options.from),
                options.until.empty() ? count - 1 : StageIndex(options.until),
                false,
                RunResult{}};
  Progress progress("run", count, "stages");
  for (int i = 0; i < count; ++i) {
    runner.Do(i);
    WriteManifest(runner.now, manifest_path);
    progress.Advance();
  }
  progress.Done();
  RunResult& result = runner.result;
  result.result_dir = result_dir;
  result.stages = runner.now.stages;
  result.wall_s = Seconds(start);
  if (fs::exists(result_dir / "report.html")) result.report = result_dir / "report.html";
  return result;
}

}  // namespace simtree::pipeline
