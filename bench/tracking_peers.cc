// Marker tracking peers, side by side with ours (issue 20): OpenCV's CSRT and KCF trackers (the
// contrib tracking module), one tracker per marker, on a capture's pull stream, written in the
// formats `simtree eval tracking` scores (boxes.csv, trajectories.csv; docs/formats.md).
//
//   tracking_peers --capture scene/ --out peers/          peers/csrt/, peers/kcf/
//   tracking_peers --capture scene/ --out peers/ --trackers csrt --init my_init.json
//
// Each peer starts from pull/init.json's pixel of each marker with a box of the size of the
// marker's true box in the init frame (gt/markers_2d.json, when the capture has it; else
// --init-box px square), the best start a peer can be given. With --min-box N each tracker's box
// is grown to at least N px about the same centre (context for trackers built for larger
// targets) and the box reported is the marker's size about its centre. Every frame is tracked on
// one thread (cv::setNumThreads(1)). A peer's 3D centre is the median valid depth inside the
// central third of its box, back-projected at the box centre with the intrinsics; a failed update
// is state lost, no position. Our tracker (the library's per-frame step, as `simtree track` runs
// it) is stepped over the same frames for its frames/s; its outputs come from `simtree track`.
//
// Frames/s: CPU time of the tracking calls of each tracker alone (this thread's clock), frames
// decoded beforehand and not counted. Printed per tracker and written to <out>/speed.json.

#include <time.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/tracking.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/track_init.h"
#include "simtree/io/trajectories.h"
#include "simtree/tracking/boxes_file.h"
#include "simtree/tracking/detail/marker_tracker.h"
#include "simtree/tracking/detail/pull_input.h"

namespace fs = std::filesystem;
using namespace simtree;

namespace {

// This thread's CPU time (s): timings that the other processes of a shared machine do not inflate.
double ThreadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Args {
  fs::path capture;
  fs::path init;  // default <capture>/pull/init.json
  fs::path out;
  std::vector<std::string> trackers = {"csrt", "kcf"};
  bool time_ours = true;
  double init_box_px = 8.0;  // box side when the capture has no gt/markers_2d.json (px)
  double min_box_px = 0.0;   // the trackers' boxes grown to at least this side (px), 0: as is
};

// One marker followed by one OpenCV tracker.
struct PeerMarker {
  int id = 0;
  cv::Ptr<cv::Tracker> tracker;  // null when the marker could not be started
  cv::Rect box;                  // the last box the tracker gave (OpenCV's integer pixels)
  cv::Size2d size;               // the marker's box size reported about the tracker box's centre
};

struct PeerRun {
  std::string name;
  std::vector<PeerMarker> markers;
  std::vector<tracking::FrameBoxes> boxes;
  Trajectories trajectories;
  double cpu_s = 0.0;
  int frames = 0;
};

cv::Ptr<cv::Tracker> MakeTracker(const std::string& name) {
  if (name == "csrt") return cv::TrackerCSRT::create();
  if (name == "kcf") return cv::TrackerKCF::create();
  throw InputError("--trackers", name, "expected csrt or kcf");
}

// The colour image as OpenCV's BGR matrix.
cv::Mat ToBgr(const RgbImage& image) {
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    auto* row = bgr.ptr<uint8_t>(y);
    const uint8_t* src = &image.pixels[static_cast<size_t>(y) * image.width * 3];
    for (int x = 0; x < image.width; ++x) {
      row[3 * x] = src[3 * x + 2];
      row[3 * x + 1] = src[3 * x + 1];
      row[3 * x + 2] = src[3 * x];
    }
  }
  return bgr;
}

// The marker's box size in the init frame: its true box when the capture has one.
std::map<int, cv::Size2d> InitBoxSizes(const fs::path& capture, int init_frame, double fallback,
                                       const std::vector<MarkerPixel>& markers) {
  std::map<int, cv::Size2d> sizes;
  for (const MarkerPixel& m : markers) sizes[m.id] = cv::Size2d(fallback, fallback);
  const fs::path gt = capture / "gt" / "markers_2d.json";
  if (!fs::exists(gt)) return sizes;
  for (const MarkerFrame2d& f : ReadMarkers2d(gt)) {
    if (f.frame != init_frame) continue;
    for (const MarkerBox2d& b : f.markers) {
      if (sizes.count(b.id) && b.box[2] > 0 && b.box[3] > 0) {
        sizes[b.id] = cv::Size2d(b.box[2], b.box[3]);
      }
    }
  }
  return sizes;
}

// OpenCV's integer box covering [x - 0.5, x + w - 0.5] in simtree's pixel-centre convention.
cv::Rect RectAround(const Eigen::Vector2d& centre, const cv::Size2d& size) {
  const int w = std::max(1, static_cast<int>(std::lround(size.width)));
  const int h = std::max(1, static_cast<int>(std::lround(size.height)));
  return {static_cast<int>(std::lround(centre.x() - 0.5 * (w - 1))),
          static_cast<int>(std::lround(centre.y() - 0.5 * (h - 1))), w, h};
}

// The 3D centre of a box [x, y, w, h] (pixel centres at integers): the median valid depth of
// the pixels in its central third (at least its centre pixel), back-projected at the box centre.
// Empty when no pixel there has depth.
std::optional<Eigen::Vector3d> BoxCentre3d(const std::array<double, 4>& box,
                                           const DepthImage& depth, const CameraIntrinsics& k) {
  const double cx = box[0] + 0.5 * box[2], cy = box[1] + 0.5 * box[3];
  const auto range = [](double lo, double len, double centre, int size) {
    int a = static_cast<int>(std::ceil(lo + len / 3)),
        b = static_cast<int>(std::floor(lo + 2 * len / 3));
    if (a > b) a = b = static_cast<int>(std::lround(centre));
    return std::pair<int, int>(std::max(a, 0), std::min(b, size - 1));
  };
  const auto [x0, x1] = range(box[0], box[2], cx, depth.width);
  const auto [y0, y1] = range(box[1], box[3], cy, depth.height);
  std::vector<uint16_t> values;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (depth.at(x, y) > 0) values.push_back(depth.at(x, y));
    }
  }
  if (values.empty()) return std::nullopt;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return k.Unproject(cx, cy, values[values.size() / 2] * k.depth_scale_m);
}

// The reported box: the marker's size about the centre of the tracker's box.
std::array<double, 4> ReportedBox(const PeerMarker& m) {
  const double cx = m.box.x + 0.5 * (m.box.width - 1), cy = m.box.y + 0.5 * (m.box.height - 1);
  return {cx - 0.5 * m.size.width, cy - 0.5 * m.size.height, m.size.width, m.size.height};
}

tracking::MarkerBox ToMarkerBox(const PeerMarker& m, bool ok) {
  tracking::MarkerBox b;
  b.marker = m.id;
  b.box = ReportedBox(m);
  b.center = {b.box[0] + 0.5 * b.box[2], b.box[1] + 0.5 * b.box[3]};
  b.state = ok ? tracking::MarkerState::kTracked : tracking::MarkerState::kLost;
  b.confidence = ok ? 1.0 : 0.0;
  return b;
}

// Starts one tracker per marker on the init frame (timed with the updates).
void StartPeer(PeerRun& run, const cv::Mat& bgr, const TrackInit& init,
               const std::map<int, cv::Size2d>& sizes, double min_box_px) {
  for (size_t i = 0; i < init.markers.size(); ++i) {
    const MarkerPixel& p = init.markers[i];
    PeerMarker& m = run.markers[i];
    const cv::Size2d size = sizes.at(p.id);
    // The marker's own size, rounded as the tracker's box will be, unless the box is grown.
    m.size = min_box_px > 0 ? size
                            : cv::Size2d(std::max(1.0, std::round(size.width)),
                                         std::max(1.0, std::round(size.height)));
    m.box = RectAround(
        p.pixel, cv::Size2d(std::max(size.width, min_box_px), std::max(size.height, min_box_px)));
    try {
      m.tracker = MakeTracker(run.name);
      m.tracker->init(bgr, m.box);
    } catch (const cv::Exception& e) {
      fmt::print(stderr, "{}: marker {}: init failed ({}); lost throughout\n", run.name, p.id,
                 e.what());
      m.tracker.reset();
    }
  }
}

// One frame: each marker's update (timed), then its box and 3D centre (not timed).
void StepPeer(PeerRun& run, const cv::Mat& bgr, const RgbdImage& image, const PullFrame& frame,
              bool is_init_frame) {
  std::vector<bool> ok(run.markers.size(), false);
  const double start = ThreadSeconds();
  for (size_t i = 0; i < run.markers.size(); ++i) {
    PeerMarker& m = run.markers[i];
    if (!m.tracker) continue;
    if (is_init_frame) {
      ok[i] = true;
      continue;
    }
    try {
      cv::Rect box = m.box;
      ok[i] = m.tracker->update(bgr, box);
      if (ok[i]) m.box = box;
    } catch (const cv::Exception&) {
      ok[i] = false;
    }
  }
  run.cpu_s += ThreadSeconds() - start;
  ++run.frames;
  tracking::FrameBoxes boxes{.frame = frame.frame, .markers = {}};
  std::vector<Eigen::Vector3d> positions;
  std::vector<bool> valid;
  for (size_t i = 0; i < run.markers.size(); ++i) {
    boxes.markers.push_back(ToMarkerBox(run.markers[i], ok[i]));
    const auto p = ok[i] ? BoxCentre3d(ReportedBox(run.markers[i]), image.depth, image.intrinsics)
                         : std::nullopt;
    positions.push_back(p.value_or(Eigen::Vector3d::Constant(std::nan(""))));
    valid.push_back(p.has_value());
  }
  run.boxes.push_back(std::move(boxes));
  run.trajectories.AddFrame(frame.frame, frame.time_s, positions, valid);
}

// Frames before the init frame: every marker lost.
void SkipPeer(PeerRun& run, const PullFrame& frame) {
  tracking::FrameBoxes boxes{.frame = frame.frame, .markers = {}};
  for (const PeerMarker& m : run.markers) boxes.markers.push_back(ToMarkerBox(m, false));
  run.boxes.push_back(std::move(boxes));
  run.trajectories.AddFrame(
      frame.frame, frame.time_s,
      std::vector<Eigen::Vector3d>(run.markers.size(), Eigen::Vector3d::Constant(std::nan(""))),
      std::vector<bool>(run.markers.size(), false));
}

// Our tracker's per-frame step over the same frames, timed the same way.
struct OursRun {
  std::optional<tracking::detail::MarkerTracker> tracker;
  double cpu_s = 0.0;
  int frames = 0;
};

void StepOurs(OursRun& ours, const RgbdImage& image, const TrackInit& init, double dt,
              const std::string& source) {
  if (!ours.tracker) {
    std::vector<int> ids;
    std::vector<Eigen::Vector2d> pixels;
    for (const MarkerPixel& m : init.markers) {
      ids.push_back(m.id);
      pixels.push_back(m.pixel);
    }
    const auto model = tracking::detail::ChooseColorModel("auto", image.color, init, source);
    ours.tracker.emplace(tracking::TrackOptions{}, model, image.intrinsics, ids, pixels);
  }
  const double start = ThreadSeconds();
  const auto result = ours.tracker->Step(image, dt);
  ours.cpu_s += ThreadSeconds() - start;
  ours.frames += result.empty() ? 0 : 1;
}

double Rate(int frames, double seconds) { return seconds > 0 ? frames / seconds : 0.0; }

void WriteOutputs(const Args& args, const std::vector<PeerRun>& runs, const OursRun& ours) {
  nlohmann::json speed = {{"capture", args.capture.string()},
                          {"trackers", nlohmann::json::object()}};
  for (const PeerRun& run : runs) {
    const fs::path dir = args.out / run.name;
    fs::create_directories(dir);
    tracking::WriteBoxesCsv(run.boxes, dir / "boxes.csv");
    WriteTrajectoriesCsv(run.trajectories, dir / "trajectories.csv");
    speed["trackers"][run.name] = {{"frames", run.frames},
                                   {"cpu_s", run.cpu_s},
                                   {"frames_per_s", Rate(run.frames, run.cpu_s)}};
    fmt::print("{}: {} frames, {:.1f} frames/s\n", run.name, run.frames,
               Rate(run.frames, run.cpu_s));
  }
  if (args.time_ours) {
    speed["trackers"]["ours"] = {{"frames", ours.frames},
                                 {"cpu_s", ours.cpu_s},
                                 {"frames_per_s", Rate(ours.frames, ours.cpu_s)}};
    fmt::print("ours: {} frames, {:.1f} frames/s\n", ours.frames, Rate(ours.frames, ours.cpu_s));
  }
  WriteFileAtomically(args.out / "speed.json", speed.dump(1) + "\n");
}

void Run(const Args& args) {
  cv::setNumThreads(1);
  const Capture capture = OpenCapture(args.capture);
  if (!capture.pull) throw InputError(args.capture.string(), "pull/", "expected a pull stream");
  const PullStream& pull = *capture.pull;
  const fs::path init_path = args.init.empty() ? args.capture / "pull" / "init.json" : args.init;
  const TrackInit init = ReadTrackInitJson(init_path);
  const size_t start = tracking::detail::CheckInit(pull, init, init_path);
  const auto sizes = InitBoxSizes(args.capture, init.frame, args.init_box_px, init.markers);
  std::vector<PeerRun> runs;
  for (const std::string& name : args.trackers) {
    MakeTracker(name);  // refuses an unknown name before any frame is read
    runs.emplace_back();
    runs.back().name = name;
    for (const MarkerPixel& m : init.markers) {
      runs.back().markers.push_back(
          PeerMarker{.id = m.id, .tracker = nullptr, .box = {}, .size = {}});
      MarkerTrack track;
      track.marker = m.id;
      runs.back().trajectories.tracks.push_back(track);
    }
  }
  OursRun ours;
  for (size_t i = 0; i < pull.frames.size(); ++i) {
    if (i < start) {
      for (PeerRun& run : runs) SkipPeer(run, pull.frames[i]);
      continue;
    }
    const RgbdImage image = LoadPullFrame(pull, i);
    const cv::Mat bgr = ToBgr(image.color);
    const double dt = i > start ? pull.frames[i].time_s - pull.frames[i - 1].time_s : 0.0;
    if (args.time_ours) StepOurs(ours, image, init, dt, init_path.string());
    for (PeerRun& run : runs) {
      if (i == start) {
        const double t0 = ThreadSeconds();
        StartPeer(run, bgr, init, sizes, args.min_box_px);
        run.cpu_s += ThreadSeconds() - t0;
      }
      StepPeer(run, bgr, image, pull.frames[i], i == start);
    }
  }
  WriteOutputs(args, runs, ours);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "OpenCV's CSRT and KCF marker trackers on a capture's pull stream, one tracker per marker "
      "started from pull/init.json with the marker's true box size, written as boxes.csv and "
      "trajectories.csv for `simtree eval tracking`; prints each tracker's frames/s (and ours) "
      "on one core.\n\nExample: tracking_peers --capture scene/ --out peers/ && "
      "simtree eval tracking peers/csrt --gt scene/"};
  Args args;
  app.add_option("--capture", args.capture, "The capture (its pull/ and, when synth, gt/)")
      ->required();
  app.add_option("--out", args.out,
                 "Folder to write: <tracker>/boxes.csv, trajectories.csv, "
                 "speed.json")
      ->required();
  app.add_option("--init", args.init, "init.json (default: <capture>/pull/init.json)");
  app.add_option("--trackers", args.trackers, "Peers to run: csrt, kcf")->delimiter(',');
  app.add_option("--init-box", args.init_box_px,
                 "Box side when the capture has no gt/markers_2d.json (px)");
  app.add_option("--min-box", args.min_box_px,
                 "Grow each tracker's box to at least this side (px) for context; the box "
                 "reported is the marker's size about the tracker box's centre");
  app.add_flag("!--no-ours", args.time_ours, "Do not time our tracker's step beside them");
  CLI11_PARSE(app, argc, argv);
  try {
    Run(args);
  } catch (const std::exception& e) {
    fmt::print(stderr, "tracking_peers: {}\n", e.what());
    return 1;
  }
  return 0;
}
