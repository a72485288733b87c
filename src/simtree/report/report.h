#pragma once
// The HTML report of a run (issue 21 item 4): one self-contained file, RESULT/report.html, that
// opens in any browser without a network. It shows what every stage left in the result folder
// and says what is missing:
//
//   run.json            the stages' table (status, wall time, one-line summary)
//   preprocess/         the views;  register/  the registration before and after, pairs
//   reconstruct/        the tree over the merged cloud (picture.png)
//   track/              overlay frames, the marker trajectories as interactive charts
//   identify/           the spectra of the marker links (interactive), the Table IV ranges
//   build/              the simulation-ready tree's table of branches
//   simulate/           the pull-and-release playing in a 3D view (three.js, orbit controls,
//                       play/pause, time slider), replayed from nodes.bin
//   render/             simulated frames beside the capture's (paper Fig. 15)
//   eval/eval.json      the scores against the truth, as tables; the paper's tables beside ours
//
// Images are inlined (base64), the JavaScript libraries too (three.js r111 and Chart.js 3 from
// the Debian packages libjs-three and libjs-chart.js, read at run time from `javascript_dir`),
// and the animation is sent compactly (docs/report.md): the rest geometry once, then per frame
// the positions of a subset of nodes quantised to 16 bits in their bounding box, with the frame
// rate and the node subset chosen so the animation fits its byte budget.
//
// Usage:
//   simtree::report::ReportOptions options;           // RESULT/report.html, at most 20 MB
//   const simtree::report::ReportResult report =
//       simtree::report::WriteReport("out/demo/result", options);
//   std::printf("%s: %.1f MB\n", report.path.c_str(), report.bytes / 1e6);

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace simtree::report {

// Where the JavaScript libraries are looked for unless ReportOptions says otherwise (CMake's
// SIMTREE_JAVASCRIPT_DIR, /usr/share/javascript by default: the Debian packages' folder).
std::filesystem::path DefaultJavaScriptDir();

struct ReportOptions {
  // The file to write; empty: `result_dir`/report.html.
  std::filesystem::path output;
  // Folder with three/three.min.js, three/examples/js/controls/OrbitControls.js and
  // chart.js/chart.min.js (libjs-three, libjs-chart.js); empty: DefaultJavaScriptDir().
  std::filesystem::path javascript_dir;
  // Without the libraries, write the page anyway with notes instead of the 3D view and charts
  // (default: throw an Error naming the missing package).
  bool allow_missing_javascript = false;
  // Upper bound of the whole file (bytes); the animation gets what the rest leaves, up to
  // `animation_max_bytes`.
  int64_t max_bytes = 20'000'000;
  int64_t animation_max_bytes = 12'000'000;
  // Images (all of them together) at most this many bytes once encoded.
  int64_t image_max_bytes = 5'000'000;
  // The animation is not sent at fewer frames per second than this (nodes are thinned first).
  double min_animation_fps = 10.0;
  // Frames shown of the tracking overlay and of the side-by-side renders.
  int overlay_frames = 4;
  int render_frames = 6;
  // Images wider than this are scaled down (pixels).
  int max_image_width = 960;
  // Rows of the branch table (a larger tree lists its first rows and says so).
  int max_branch_rows = 2000;
  // Interactive charts keep at most this many samples per curve.
  int max_chart_samples = 1500;
  std::string title;  // default: "simtree report: <result folder name>"

  // Throws Error for a value out of range (sizes, counts, fps).
  void Validate() const;
};

// What one section of the page holds.
struct SectionReport {
  std::string id;     // "stages", "views", "registration", ...
  std::string title;  // as shown
  bool present = false;
  std::vector<std::string> notes;  // what is missing or was left out
};

struct AnimationReport {
  bool present = false;
  int nodes = 0, frames = 0;              // in nodes.bin
  int sent_nodes = 0, sent_frames = 0;    // in the page
  int node_stride = 1, frame_stride = 1;  // every k-th node of a branch (and its tip), frame
  double fps = 0.0, sent_fps = 0.0;
  double quantisation_step_m = 0.0;  // largest of the three axes' steps
  int64_t bytes = 0;                 // of the animation's data in the page
};

struct ReportResult {
  std::filesystem::path path;
  int64_t bytes = 0;
  std::vector<SectionReport> sections;
  AnimationReport animation;
  int64_t image_bytes = 0;         // inlined images
  int64_t library_bytes = 0;       // inlined JavaScript libraries
  std::vector<std::string> notes;  // every section's notes, prefixed by its title

  const SectionReport* Find(const std::string& id) const;
};

// Reads what `result_dir` holds and writes the report (atomically: the file appears whole or not
// at all). Missing parts become notes on the page, never errors; a part that is there but cannot
// be read becomes a note with the reader's message. Throws InputError when `result_dir` is not a
// folder, Error when a JavaScript library is missing (unless allowed) or the page would exceed
// `max_bytes`, IoError when the file cannot be written.
ReportResult WriteReport(const std::filesystem::path& result_dir,
                         const ReportOptions& options = {});

// The page as a string, without writing it (what WriteReport writes).
std::string BuildReportHtml(const std::filesystem::path& result_dir, const ReportOptions& options,
                            ReportResult* result = nullptr);

}  // namespace simtree::report
