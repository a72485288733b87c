#include "simtree/io/tum_rgbd.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/detail/time_association.h"

namespace simtree {

namespace fs = std::filesystem;

void TumRgbdOptions::Validate() const {
  CheckOption(intrinsics.has_value(), "TUM RGB-D options", "intrinsics",
              "expected the camera: TUM's lists carry none (an intrinsics file, or one of " +
                  fmt::format("{}", fmt::join(TumCameraNames(), ", ")) + ")");
  CheckPositive("depth_factor", depth_factor);
  CheckNonNegative("max_time_difference_s", max_time_difference_s);
}

std::vector<TumListEntry> ReadTumList(const fs::path& path) {
  if (!fs::is_regular_file(path)) {
    throw InputError(path.string(), "", "expected a TUM list (\"timestamp filename\" per line)");
  }
  std::istringstream in(ReadFile(path));
  std::vector<TumListEntry> entries;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    std::istringstream fields(line.substr(start));
    std::string stamp, file;
    fields >> stamp >> file;
    double t = 0;
    const auto [end, ec] = std::from_chars(stamp.data(), stamp.data() + stamp.size(), t);
    const std::string where = fmt::format("line {}", number);
    if (ec != std::errc() || end != stamp.data() + stamp.size() || !std::isfinite(t) ||
        file.empty()) {
      throw InputError(path.string(), where,
                       fmt::format("expected \"timestamp filename\", got \"{}\"", line));
    }
    if (!entries.empty() && t <= entries.back().time_s) {
      throw InputError(path.string(), where,
                       fmt::format("expected a time after the previous line's {:.6f}, got {:.6f} "
                                   "(timestamps must increase)",
                                   entries.back().time_s, t));
    }
    const fs::path resolved = path.parent_path() / file;
    if (!fs::is_regular_file(resolved)) {
      throw InputError(path.string(), where,
                       fmt::format("names {}, which does not exist", resolved.string()));
    }
    entries.push_back({t, resolved});
  }
  if (entries.empty()) throw InputError(path.string(), "", "expected entries, the list has none");
  return entries;
}

namespace {

struct NamedCamera {
  const char* name;
  double fx, fy, cx, cy;
  bool distorted;
};
// TUM RGB-D benchmark, "Intrinsic Camera Calibration of the Kinect" (colour cameras, 640x480).
constexpr NamedCamera kTumCameras[] = {
    {"tum-fr1", 517.3, 516.5, 318.6, 255.3, true},
    {"tum-fr2", 520.9, 521.0, 325.1, 249.7, true},
    {"tum-fr3", 535.4, 539.2, 320.1, 247.6, false},
    {"tum-default", 525.0, 525.0, 319.5, 239.5, false},
};

}  // namespace

std::vector<std::string> TumCameraNames() {
  std::vector<std::string> names;
  for (const NamedCamera& c : kTumCameras) names.emplace_back(c.name);
  return names;
}

CameraIntrinsics TumCamera(const std::string& name) {
  for (const NamedCamera& c : kTumCameras) {
    if (name != c.name) continue;
    if (c.distorted) {
      spdlog::warn(
          "{}: TUM's {} colour images keep their lens distortion, which simtree does not "
          "remove; points far from the image centre are off by a few pixels",
          name, name.substr(4));
    }
    return {640, 480, c.fx, c.fy, c.cx, c.cy, 0.001};
  }
  throw InputError("camera", name,
                   fmt::format("expected one of {}", fmt::join(TumCameraNames(), ", ")));
}

bool IsTumRgbdFolder(const fs::path& folder) {
  return fs::is_regular_file(folder / "rgb.txt") && fs::is_regular_file(folder / "depth.txt");
}

std::unique_ptr<RgbdSequence> OpenTumRgbd(const fs::path& folder, const TumRgbdOptions& options) {
  options.Validate();
  if (!IsTumRgbdFolder(folder)) {
    throw InputError(folder.string(), "", "expected a TUM RGB-D folder (rgb.txt and depth.txt)");
  }
  const std::vector<TumListEntry> rgb = ReadTumList(folder / "rgb.txt");
  const std::vector<TumListEntry> depth = ReadTumList(folder / "depth.txt");
  std::vector<double> rgb_t, depth_t;
  for (const TumListEntry& e : rgb) rgb_t.push_back(e.time_s);
  for (const TumListEntry& e : depth) depth_t.push_back(e.time_s);
  const auto pairs = io_detail::AssociateByTime(rgb_t, depth_t, options.max_time_difference_s);
  if (pairs.empty()) {
    throw InputError(folder.string(), "",
                     fmt::format("expected colour and depth frames within {} s of each other, "
                                 "found none (rgb.txt {:.3f}-{:.3f} s, depth.txt {:.3f}-{:.3f} s)",
                                 options.max_time_difference_s, rgb_t.front(), rgb_t.back(),
                                 depth_t.front(), depth_t.back()));
  }
  std::vector<RgbdFileFrame> frames;
  double worst = 0;
  for (const auto& [i, j] : pairs) {
    frames.push_back({rgb[i].time_s, rgb[i].file, depth[j].file});
    worst = std::max(worst, std::abs(rgb[i].time_s - depth[j].time_s));
  }
  spdlog::info("{}: {} colour and {} depth frames, {} paired (at most {:.1f} ms apart)",
               folder.string(), rgb.size(), depth.size(), frames.size(), worst * 1e3);
  return std::make_unique<RgbdFileSequence>(folder.string(), "tum_rgbd", *options.intrinsics,
                                            options.depth_factor, std::move(frames));
}

}  // namespace simtree
