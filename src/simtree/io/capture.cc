#include "simtree/io/capture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/json_util.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

using ojson = nlohmann::ordered_json;

// Images larger than this are not depth-camera frames (and would not fit a sane buffer).
constexpr int kMaxImageSide = 16384;

std::string Dump(const ojson& doc) { return doc.dump(1) + "\n"; }

void RequireFile(const fs::path& path, const std::string& what) {
  if (!fs::is_regular_file(path)) {
    throw InputError(path.string(), "", fmt::format("missing ({})", what));
  }
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string Trim(std::string s) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

// A relative path inside pull/ (no absolute paths, no "..": a capture folder must be movable).
void CheckRelative(const std::string& path, const std::string& source, const std::string& where) {
  const fs::path p(path);
  if (path.empty()) throw InputError(source, where, "expected a path, got an empty cell");
  if (p.is_absolute()) {
    throw InputError(source, where,
                     fmt::format("expected a path relative to pull/, got \"{}\"", path));
  }
  for (const auto& part : p) {
    if (part == "..") {
      throw InputError(source, where,
                       fmt::format("expected a path inside pull/, got \"{}\"", path));
    }
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Intrinsics

Eigen::Vector2d CameraIntrinsics::Project(const Eigen::Vector3d& p) const {
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
}

Eigen::Vector3d CameraIntrinsics::Unproject(double u, double v, double z) const {
  return {(u - cx) / fx * z, (v - cy) / fy * z, z};
}

double CameraIntrinsics::HorizontalFov() const {
  return std::atan((cx + 0.5) / fx) + std::atan((width - 0.5 - cx) / fx);
}

double CameraIntrinsics::VerticalFov() const {
  return std::atan((cy + 0.5) / fy) + std::atan((height - 0.5 - cy) / fy);
}

void ValidateIntrinsics(const CameraIntrinsics& k, const std::string& source) {
  if (k.width <= 0 || k.height <= 0 || k.width > kMaxImageSide || k.height > kMaxImageSide) {
    throw InputError(source, "width, height",
                     fmt::format("expected an image size between 1 and {} pixels, got {}x{}",
                                 kMaxImageSide, k.width, k.height));
  }
  for (const auto& [name, value] : {std::pair{"fx", k.fx}, std::pair{"fy", k.fy}}) {
    if (!std::isfinite(value) || value <= 0) {
      throw InputError(source, name,
                       fmt::format("expected a positive focal length in pixels, got {}", value));
    }
  }
  // The principal point may sit off-centre, but not far outside the image.
  if (!std::isfinite(k.cx) || k.cx < -k.width || k.cx > 2.0 * k.width) {
    throw InputError(source, "cx",
                     fmt::format("expected a principal point near the image "
                                 "(0..{}), got {}",
                                 k.width, k.cx));
  }
  if (!std::isfinite(k.cy) || k.cy < -k.height || k.cy > 2.0 * k.height) {
    throw InputError(source, "cy",
                     fmt::format("expected a principal point near the image "
                                 "(0..{}), got {}",
                                 k.height, k.cy));
  }
  if (!std::isfinite(k.depth_scale_m) || k.depth_scale_m <= 0 || k.depth_scale_m > 1.0) {
    throw InputError(source, "depth_scale_m",
                     fmt::format("expected metres per depth unit in (0, 1] (0.001 for "
                                 "millimetres), got {}",
                                 k.depth_scale_m));
  }
}

CameraIntrinsics ReadIntrinsicsJson(const fs::path& path) {
  RequireFile(path, "camera intrinsics JSON");
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  doc.ExpectObject();
  CameraIntrinsics k;
  k.width = doc.Integer("width");
  k.height = doc.Integer("height");
  k.fx = doc.Number("fx");
  k.fy = doc.Number("fy");
  k.cx = doc.Number("cx");
  k.cy = doc.Number("cy");
  k.depth_scale_m = doc.Number("depth_scale_m");
  ValidateIntrinsics(k, file.source);
  return k;
}

void WriteIntrinsicsJson(const CameraIntrinsics& k, const fs::path& path) {
  ValidateIntrinsics(k, path.string());
  const ojson doc = {{"width", k.width},
                     {"height", k.height},
                     {"fx", k.fx},
                     {"fy", k.fy},
                     {"cx", k.cx},
                     {"cy", k.cy},
                     {"depth_scale_m", k.depth_scale_m}};
  WriteFileAtomically(path, Dump(doc));
}

// ---------------------------------------------------------------------------------------------
// capture.json

CaptureInfo ReadCaptureInfo(const fs::path& path) {
  RequireFile(path, "capture description capture.json");
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kCaptureFormat, kCaptureFormatVersion);
  CaptureInfo info;
  info.sensor = doc.String("sensor");
  if (const auto species = doc.Find("species")) info.species = species->String();
  if (const auto notes = doc.Find("notes")) info.notes = notes->String();
  return info;
}

void WriteCaptureInfo(const CaptureInfo& info, const fs::path& path) {
  const ojson doc = {{"format", kCaptureFormat},
                     {"version", kCaptureFormatVersion},
                     {"sensor", info.sensor},
                     {"species", info.species},
                     {"notes", info.notes}};
  WriteFileAtomically(path, Dump(doc));
}

// ---------------------------------------------------------------------------------------------
// markers.json

std::vector<MarkerLink> ReadMarkersJson(const fs::path& path) {
  RequireFile(path, "marker list markers.json");
  const JsonDocument file = ReadJsonDocument(path);
  const JsonNode doc = file.root();
  CheckFormat(doc, kMarkersFormat, kMarkersFormatVersion);
  const JsonNode list = doc.Field("markers");
  if (list.size() == 0) list.Fail("expected at least one marker, got an empty list");
  std::vector<MarkerLink> markers;
  std::map<int, size_t> index_of;
  for (const JsonNode& item : list.Items()) {
    MarkerLink m;
    const JsonNode id = item.Field("id");
    m.id = id.Integer();
    if (m.id < 0) id.Fail(fmt::format("expected an id >= 0, got {}", m.id));
    const auto label = item.Find("label");
    m.label = label ? label->String() : fmt::format("M{}", m.id);
    m.parent = item.Integer("parent");
    if (const auto branch = item.Find("branch")) {
      m.branch = branch->Integer();
      if (*m.branch < 0) branch->Fail(fmt::format("expected a branch id >= 0, got {}", *m.branch));
    }
    if (!index_of.emplace(m.id, markers.size()).second) {
      id.Fail(fmt::format("marker id {} appears twice", m.id));
    }
    markers.push_back(m);
  }
  int roots = 0;
  for (size_t i = 0; i < markers.size(); ++i) {
    const std::string at = Member(Element("markers", i), "parent");
    const MarkerLink& m = markers[i];
    if (m.parent == -1) {
      ++roots;
      continue;
    }
    if (!index_of.count(m.parent)) {
      doc.FailAt(at, fmt::format("marker {} links to marker {}, which is not in the list", m.id,
                                 m.parent));
    }
    // Walk to the root; more steps than markers means a cycle.
    int current = m.parent;
    for (size_t steps = 0; current != -1; ++steps) {
      if (steps > markers.size() || current == m.id) {
        doc.FailAt(at, fmt::format("the links from marker {} form a cycle", m.id));
      }
      current = markers[index_of.at(current)].parent;
    }
  }
  if (roots != 1) {
    doc.FailAt(
        "markers",
        fmt::format("expected exactly one root marker (parent -1, on the trunk), got {}", roots));
  }
  return markers;
}

void WriteMarkersJson(const std::vector<MarkerLink>& markers, const fs::path& path) {
  ojson list = ojson::array();
  for (const MarkerLink& m : markers) {
    ojson entry = {{"id", m.id}, {"label", m.label}, {"parent", m.parent}};
    if (m.branch) entry["branch"] = *m.branch;
    list.push_back(entry);
  }
  const ojson doc = {
      {"format", kMarkersFormat}, {"version", kMarkersFormatVersion}, {"markers", list}};
  WriteFileAtomically(path, Dump(doc));
}

// ---------------------------------------------------------------------------------------------
// frames.csv

std::vector<PullFrame> ReadFramesCsv(const fs::path& path) {
  RequireFile(path, "frame list frames.csv");
  const std::string source = path.string();
  std::istringstream in(ReadFile(path));
  std::string line;
  int line_number = 0;
  bool header_seen = false;
  std::vector<PullFrame> frames;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (Trim(line).empty() || line[0] == '#') continue;
    const std::string where = fmt::format("line {}", line_number);
    const std::vector<std::string> cells = SplitCsvLine(line);
    if (!header_seen) {
      if (cells.size() != 4 || Trim(cells[0]) != "frame" || Trim(cells[1]) != "time_s" ||
          Trim(cells[2]) != "color" || Trim(cells[3]) != "depth") {
        throw InputError(source, where,
                         fmt::format("expected the header \"frame,time_s,color,depth\", got "
                                     "\"{}\"",
                                     line));
      }
      header_seen = true;
      continue;
    }
    if (cells.size() != 4) {
      throw InputError(
          source, where,
          fmt::format("expected 4 cells (frame,time_s,color,depth), got {}", cells.size()));
    }
    PullFrame f;
    try {
      size_t used = 0;
      f.frame = std::stoi(Trim(cells[0]), &used);
      if (used != Trim(cells[0]).size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw InputError(source, where + ", frame",
                       fmt::format("expected an integer frame number, got \"{}\"", cells[0]));
    }
    try {
      size_t used = 0;
      f.time_s = std::stod(Trim(cells[1]), &used);
      if (used != Trim(cells[1]).size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw InputError(source, where + ", time_s",
                       fmt::format("expected a time in seconds, got \"{}\"", cells[1]));
    }
    if (!std::isfinite(f.time_s)) {
      throw InputError(source, where + ", time_s", "expected a finite time in seconds");
    }
    f.color = Trim(cells[2]);
    f.depth = Trim(cells[3]);
    CheckRelative(f.color, source, where + ", color");
    CheckRelative(f.depth, source, where + ", depth");
    if (!frames.empty()) {
      if (f.frame <= frames.back().frame) {
        throw InputError(source, where + ", frame",
                         fmt::format("expected frames in increasing order, got {} after {}",
                                     f.frame, frames.back().frame));
      }
      if (f.time_s <= frames.back().time_s) {
        throw InputError(source, where + ", time_s",
                         fmt::format("expected increasing times, got {} s after {} s", f.time_s,
                                     frames.back().time_s));
      }
    }
    frames.push_back(std::move(f));
  }
  if (!header_seen) {
    throw InputError(source, "",
                     "expected the header \"frame,time_s,color,depth\", the file is empty");
  }
  if (frames.empty()) throw InputError(source, "", "expected at least one frame, got none");
  return frames;
}

void WriteFramesCsv(const std::vector<PullFrame>& frames, const fs::path& path) {
  std::string out = "frame,time_s,color,depth\n";
  for (const PullFrame& f : frames) {
    out += fmt::format("{},{:.6f},{},{}\n", f.frame, f.time_s, f.color, f.depth);
  }
  WriteFileAtomically(path, out);
}

double PullStream::FrameRate() const {
  if (frames.size() < 2) return 0.0;
  const double span = frames.back().time_s - frames.front().time_s;
  return span > 0 ? static_cast<double>(frames.size() - 1) / span : 0.0;
}

// ---------------------------------------------------------------------------------------------
// The folder

Capture OpenCapture(const fs::path& root) {
  if (!fs::is_directory(root)) {
    throw InputError(root.string(), "", "expected a capture folder, no such folder");
  }
  Capture capture;
  capture.root = root;
  capture.info = ReadCaptureInfo(root / "capture.json");

  const fs::path scans = root / "scans";
  if (fs::is_directory(scans)) {
    for (const auto& entry : fs::directory_iterator(scans)) {
      if (!entry.is_directory()) continue;
      ScanView view;
      view.name = entry.path().filename().string();
      if (view.name.empty() || view.name[0] == '.') continue;  // staging or hidden folders
      view.directory = entry.path();
      view.intrinsics = ReadIntrinsicsJson(view.directory / "intrinsics.json");
      RequireFile(view.color_path(), "colour image of view " + view.name);
      RequireFile(view.depth_path(), "depth image of view " + view.name);
      capture.views.push_back(std::move(view));
    }
    std::sort(capture.views.begin(), capture.views.end(),
              [](const ScanView& a, const ScanView& b) { return a.name < b.name; });
    if (capture.views.empty()) {
      throw InputError(scans.string(), "", "expected view folders (view_00, ...), found none");
    }
  }

  const fs::path pull_dir = root / "pull";
  if (fs::is_directory(pull_dir)) {
    PullStream pull;
    pull.directory = pull_dir;
    pull.intrinsics = ReadIntrinsicsJson(pull_dir / "intrinsics.json");
    pull.frames = ReadFramesCsv(pull_dir / "frames.csv");
    for (size_t i = 0; i < pull.frames.size(); ++i) {
      RequireFile(
          pull_dir / pull.frames[i].color,
          fmt::format("colour image of frame {} named in frames.csv", pull.frames[i].frame));
      RequireFile(pull_dir / pull.frames[i].depth,
                  fmt::format("depth image of frame {} named in frames.csv", pull.frames[i].frame));
    }
    if (fs::exists(pull_dir / "markers.json")) {
      pull.markers = ReadMarkersJson(pull_dir / "markers.json");
      pull.has_markers = true;
    }
    capture.pull = std::move(pull);
  }

  if (capture.views.empty() && !capture.pull) {
    throw InputError(root.string(), "",
                     "expected scans/ (multi-view scans) or pull/ (a pull-test stream), found "
                     "neither");
  }
  return capture;
}

void ValidateRgbd(const RgbdImage& image, const std::string& color_source,
                  const std::string& depth_source) {
  const CameraIntrinsics& k = image.intrinsics;
  const auto check_size = [&](int w, int h, const std::string& source) {
    if (w != k.width || h != k.height) {
      throw InputError(source, "",
                       fmt::format("expected {}x{} pixels (the size in intrinsics.json), got "
                                   "{}x{}",
                                   k.width, k.height, w, h));
    }
  };
  check_size(image.color.width, image.color.height, color_source);
  check_size(image.depth.width, image.depth.height, depth_source);
  const bool any_depth = std::any_of(image.depth.pixels.begin(), image.depth.pixels.end(),
                                     [](uint16_t d) { return d != 0; });
  if (!any_depth) {
    throw InputError(depth_source, "",
                     "expected depth measurements, every pixel is 0 (no measurement)");
  }
}

RgbdImage LoadScanView(const ScanView& view) {
  RgbdImage image;
  image.intrinsics = view.intrinsics;
  image.color = ReadColorImage(view.color_path());
  image.depth = ReadDepthImage(view.depth_path());
  ValidateRgbd(image, view.color_path().string(), view.depth_path().string());
  return image;
}

RgbdImage LoadPullFrame(const PullStream& pull, size_t index) {
  if (index >= pull.frames.size()) {
    throw Error(fmt::format("LoadPullFrame: frame index {} out of range (the stream has {})", index,
                            pull.frames.size()));
  }
  const PullFrame& f = pull.frames[index];
  RgbdImage image;
  image.intrinsics = pull.intrinsics;
  image.color = ReadColorImage(pull.directory / f.color);
  image.depth = ReadDepthImage(pull.directory / f.depth);
  ValidateRgbd(image, (pull.directory / f.color).string(), (pull.directory / f.depth).string());
  return image;
}

void WriteScanView(const fs::path& capture_root, const std::string& view_name,
                   const RgbdImage& image, const PngOptions& png) {
  const fs::path dir = capture_root / "scans" / view_name;
  ValidateRgbd(image, (dir / "color.png").string(), (dir / "depth.png").string());
  fs::create_directories(dir);
  WritePng(image.color, dir / "color.png", png);
  WritePng(image.depth, dir / "depth.png", png);
  WriteIntrinsicsJson(image.intrinsics, dir / "intrinsics.json");
}

PullFrame WritePullFrame(const fs::path& pull_directory, int frame, double time_s,
                         const RgbImage& color, const DepthImage& depth, const PngOptions& png) {
  PullFrame row;
  row.frame = frame;
  row.time_s = time_s;
  row.color = fmt::format("color/{:06d}.png", frame);
  row.depth = fmt::format("depth/{:06d}.png", frame);
  fs::create_directories(pull_directory / "color");
  fs::create_directories(pull_directory / "depth");
  WritePng(color, pull_directory / row.color, png);
  WritePng(depth, pull_directory / row.depth, png);
  return row;
}

}  // namespace simtree
