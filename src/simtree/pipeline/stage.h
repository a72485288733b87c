#pragma once
// The stage table of `simtree run`: each stage's name, the files it reads (from the capture or
// from earlier stages), what it writes, the options it depends on and the function that does it.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/capture.h"

namespace simtree::pipeline {

struct RunOptions;

// What a stage function gets.
struct StageContext {
  const Capture& capture;
  std::filesystem::path capture_dir;  // the capture folder
  std::filesystem::path result_dir;   // the result folder (earlier stages' folders are in it)
  const RunOptions& options;
  // Where the stage writes its outputs: a staging folder swapped into result_dir/<name> when the
  // stage succeeds (the report stage: the result folder itself).
  std::filesystem::path out_dir;

  std::filesystem::path Result(const std::string& relative) const { return result_dir / relative; }
};

struct Stage {
  std::string name;
  // Read: "capture/<path>" in the capture folder, otherwise relative to the result folder.
  std::vector<std::string> inputs;
  // Written, relative to the result folder (a stage's folder, or report.html).
  std::vector<std::string> outputs;
  // The options the stage's result depends on (part of its input fingerprint).
  std::function<nlohmann::ordered_json(const RunOptions&)> options;
  // Does the work; returns the one-line summary. Throws on failure.
  std::function<std::string(const StageContext&)> run;
  // true: the outputs are written into a staging copy of result_dir/<name> (out_dir); false:
  // the function writes its outputs atomically itself (out_dir = result_dir).
  bool folder = true;
};

// The stages of `simtree run`, in order.
const std::vector<Stage>& StageTable();

}  // namespace simtree::pipeline
