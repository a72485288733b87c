// The set of captures a registration benchmark runs on: synthetic captures made once per species
// and seed and kept in a cache between runs (only their scans are used, so the pull stream is as
// short and sparse as synth allows), or capture folders with gt/ given on the command line; and
// the markdown and JSON the benchmark writes of its rows. Shared by registration_failfast and
// registration_pull_camera.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "simtree/synth/synth.h"

namespace simtree::bench {

struct CaptureSetArgs {
  std::vector<std::string> species = {"acer_palmatum", "magnolia", "acer_rubrum"};
  int seeds = 2, first_seed = 1;
  int views = 0;  // scan views per synthetic capture (0: synth's default)
  std::vector<std::string> captures;
  std::filesystem::path cache =
      std::filesystem::temp_directory_path() / "simtree_registration_bench";
  std::string markdown_path, json_path;

  // --species, --seeds, --first-seed, --captures, --cache, --markdown, --json.
  void AddOptions(CLI::App& app) {
    app.add_option("--species", species, "Species presets to synthesise")->capture_default_str();
    app.add_option("--seeds", seeds, "Seeds per species, from --first-seed")->capture_default_str();
    app.add_option("--first-seed", first_seed, "First seed")->capture_default_str();
    app.add_option("--captures", captures, "Capture folders with gt/ instead");
    app.add_option("--cache", cache, "Where synthetic captures are kept between runs")
        ->capture_default_str();
    app.add_option("--markdown", markdown_path, "The table as markdown");
    app.add_option("--json", json_path, "Every row as JSON");
  }
};

struct CaptureEntry {
  std::string label;  // "species seed N", or the folder given
  std::filesystem::path root;
};

// The synthetic capture of one species and seed, made when the cache lacks it: 4.5 s of pull
// stream at 2 frames a second, no contact sheet.
inline std::filesystem::path CachedSynthCapture(const CaptureSetArgs& args,
                                                const std::string& species, uint64_t seed) {
  const std::filesystem::path dir =
      args.cache / fmt::format("{}_seed{}_views{}_fps2", species, seed, args.views);
  // synth writes gt/synth.json last: a capture killed mid-synth is made again.
  if (!std::filesystem::exists(dir / "gt" / "synth.json")) {
    synth::SynthOptions options;
    options.species = species;
    options.seed = seed;
    options.views = args.views;
    options.duration_s = 4.5;
    options.fps = 2.0;
    options.contact_sheet = false;
    fmt::print(stderr, "synth {} seed {} -> {}\n", species, seed, dir.string());
    synth::RunSynth(options, dir);
  }
  return dir;
}

// The captures given, else the species x seeds synthetic ones (made as needed).
inline std::vector<CaptureEntry> ResolveCaptures(const CaptureSetArgs& args) {
  std::vector<CaptureEntry> entries;
  if (!args.captures.empty()) {
    for (const std::string& c : args.captures) entries.push_back({c, c});
    return entries;
  }
  for (const std::string& species : args.species) {
    for (int s = 0; s < args.seeds; ++s) {
      const uint64_t seed = static_cast<uint64_t>(args.first_seed + s);
      entries.push_back(
          {fmt::format("{} seed {}", species, seed), CachedSynthCapture(args, species, seed)});
    }
  }
  return entries;
}

// The markdown to standard output and, when asked, to --markdown; the JSON to --json.
inline void WriteOutputs(const CaptureSetArgs& args, const std::string& markdown,
                         const nlohmann::ordered_json& json) {
  fmt::print("{}", markdown);
  if (!args.markdown_path.empty()) std::ofstream(args.markdown_path) << markdown;
  if (!args.json_path.empty()) std::ofstream(args.json_path) << json.dump(1) << "\n";
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

inline double Largest(const std::vector<double>& v) {
  return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}

}  // namespace simtree::bench
