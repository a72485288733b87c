#include "simtree/io/realsense_bag.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/detail/ros_bag.h"
#include "simtree/io/detail/time_association.h"

namespace simtree {

namespace fs = std::filesystem;
using io_detail::RosBagIndex;
using io_detail::RosConnection;
using io_detail::RosMessageRef;
using io_detail::RosReader;

namespace {

constexpr const char* kImage = "sensor_msgs/Image";
constexpr const char* kCameraInfo = "sensor_msgs/CameraInfo";

// sensor_msgs/Image, decoded as far as this reader needs.
struct RosImage {
  double stamp_s = 0;
  uint32_t width = 0, height = 0, step = 0;
  std::string encoding;
  bool big_endian = false;
  std::string data;
};

double ReadStamp(RosReader& r) {
  r.U32();  // seq
  const uint32_t sec = r.U32();
  const uint32_t nsec = r.U32();
  r.String();  // frame_id
  return sec + nsec * 1e-9;
}

RosImage ParseImage(const std::string& bytes, const std::string& what) {
  RosReader r(bytes, what);
  RosImage image;
  image.stamp_s = ReadStamp(r);
  image.height = r.U32();
  image.width = r.U32();
  image.encoding = r.String();
  image.big_endian = r.U8() != 0;
  image.step = r.U32();
  image.data = r.Bytes();
  return image;
}

CameraIntrinsics ParseCameraInfo(const std::string& bytes, const std::string& what) {
  RosReader r(bytes, what);
  ReadStamp(r);
  CameraIntrinsics k;
  k.height = static_cast<int>(r.U32());
  k.width = static_cast<int>(r.U32());
  r.String();                  // distortion_model
  const uint32_t d = r.U32();  // D
  r.Skip(size_t{d} * 8);
  double m[9];
  for (double& v : m) v = r.F64();  // K, row-major
  k.fx = m[0];
  k.cx = m[2];
  k.fy = m[4];
  k.cy = m[5];
  ValidateIntrinsics(k, what);
  return k;
}

int Channels(const std::string& encoding) {
  if (encoding == "rgb8" || encoding == "bgr8") return 3;
  if (encoding == "rgba8" || encoding == "bgra8") return 4;
  return 0;
}
bool IsDepth(const std::string& encoding) {
  return encoding == "16UC1" || encoding == "mono16" || encoding == "z16";
}

// One image topic: its connection and its messages in time order.
struct Stream {
  const RosConnection* connection = nullptr;
  std::vector<RosMessageRef> messages;
  std::vector<double> stamps_s;
  std::string encoding;
};

class BagSequence : public RgbdSequence {
 public:
  BagSequence(fs::path path, std::unique_ptr<RosBagIndex> index, CameraIntrinsics intrinsics,
              double units_per_m, std::vector<std::pair<RosMessageRef, RosMessageRef>> frames,
              std::vector<double> times)
      : path_(std::move(path)),
        source_(path_.string()),
        index_(std::move(index)),
        reader_(path_, *index_),
        intrinsics_(intrinsics),
        units_per_m_(units_per_m),
        frames_(std::move(frames)),
        times_(std::move(times)) {
    intrinsics_.depth_scale_m = 0.001;
  }
  const std::string& source() const override { return source_; }
  std::string sensor() const override { return "realsense_bag"; }
  const CameraIntrinsics& intrinsics() const override { return intrinsics_; }
  size_t size() const override { return frames_.size(); }
  double time_s(size_t index) const override { return times_.at(index); }
  RgbdImage Load(size_t index) const override {
    RgbdImage image;
    image.intrinsics = intrinsics_;
    image.color = LoadColor(index);
    const RosImage raw = Message(frames_.at(index).second, "depth");
    Check(raw, 2, "depth");
    DepthImage depth(intrinsics_.width, intrinsics_.height);
    for (int y = 0; y < depth.height; ++y) {
      const char* row = raw.data.data() + size_t{raw.step} * y;
      for (int x = 0; x < depth.width; ++x) {
        uint16_t v;
        std::memcpy(&v, row + 2 * x, 2);
        depth.at(x, y) = raw.big_endian ? static_cast<uint16_t>((v >> 8) | (v << 8)) : v;
      }
    }
    image.depth = DepthToMillimetres(depth, units_per_m_, nullptr);
    return image;
  }
  RgbImage LoadColor(size_t index) const override {
    const RosImage raw = Message(frames_.at(index).first, "colour");
    const int channels = Channels(raw.encoding);
    Check(raw, channels, "colour");
    const bool bgr = raw.encoding[0] == 'b';
    RgbImage color(intrinsics_.width, intrinsics_.height);
    for (int y = 0; y < color.height; ++y) {
      const auto* row = reinterpret_cast<const uint8_t*>(raw.data.data()) + size_t{raw.step} * y;
      for (int x = 0; x < color.width; ++x) {
        for (int c = 0; c < 3; ++c) color.at(x, y, c) = row[channels * x + (bgr ? 2 - c : c)];
      }
    }
    return color;
  }

 private:
  RosImage Message(const RosMessageRef& ref, const char* what) const {
    const std::string where = fmt::format("{}: {} image at byte {}", source_, what, ref.offset);
    return ParseImage(reader_.Read(ref), where);
  }
  void Check(const RosImage& raw, int bytes_per_pixel, const char* what) const {
    if (static_cast<int>(raw.width) != intrinsics_.width ||
        static_cast<int>(raw.height) != intrinsics_.height ||
        raw.step < raw.width * bytes_per_pixel || raw.data.size() < size_t{raw.step} * raw.height) {
      throw InputError(source_, fmt::format("{} image at {:.6f} s", what, raw.stamp_s),
                       fmt::format("expected {}x{} pixels of {} bytes, got {}x{} with step {} "
                                   "and {} bytes",
                                   intrinsics_.width, intrinsics_.height, bytes_per_pixel,
                                   raw.width, raw.height, raw.step, raw.data.size()));
    }
  }
  fs::path path_;
  std::string source_;
  std::unique_ptr<RosBagIndex> index_;
  mutable io_detail::RosBagReader reader_;  // keeps the last decompressed chunk
  CameraIntrinsics intrinsics_;
  double units_per_m_;
  std::vector<std::pair<RosMessageRef, RosMessageRef>> frames_;
  std::vector<double> times_;
};

// Every image topic with its first message's encoding; messages sorted by header stamp, repeated
// stamps dropped.
std::vector<Stream> ImageStreams(const RosBagIndex& index, io_detail::RosBagReader& reader,
                                 const fs::path& path) {
  std::vector<Stream> streams;
  for (const RosConnection& c : index.connections) {
    if (c.type != kImage) continue;
    Stream s;
    s.connection = &c;
    std::vector<std::pair<double, RosMessageRef>> timed;
    for (const RosMessageRef& m : index.messages) {
      if (m.connection != c.id) continue;
      // The header comes first: read only it.
      const std::string bytes = reader.Read(m, 4096);
      RosReader r(bytes, path.string() + ": " + c.topic);
      const double stamp = ReadStamp(r);
      if (s.encoding.empty()) {
        r.U32();
        r.U32();
        s.encoding = r.String();
      }
      timed.emplace_back(stamp > 0 ? stamp : m.time_ns * 1e-9, m);
    }
    std::stable_sort(timed.begin(), timed.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [t, m] : timed) {
      if (!s.stamps_s.empty() && t <= s.stamps_s.back()) continue;
      s.stamps_s.push_back(t);
      s.messages.push_back(m);
    }
    if (!s.messages.empty()) streams.push_back(std::move(s));
  }
  return streams;
}

// The camera info topic sharing the longest topic prefix with `image_topic`.
std::optional<CameraIntrinsics> CameraOf(const std::string& image_topic, const RosBagIndex& index,
                                         io_detail::RosBagReader& reader, const fs::path& path) {
  const RosConnection* best = nullptr;
  size_t best_prefix = 0;
  for (const RosConnection& c : index.connections) {
    if (c.type != kCameraInfo) continue;
    const size_t prefix = static_cast<size_t>(
        std::mismatch(c.topic.begin(), c.topic.end(), image_topic.begin(), image_topic.end())
            .first -
        c.topic.begin());
    if (!best || prefix > best_prefix) best = &c, best_prefix = prefix;
  }
  if (!best) return std::nullopt;
  for (const RosMessageRef& m : index.messages) {
    if (m.connection == best->id) {
      return ParseCameraInfo(reader.Read(m), path.string() + ": " + best->topic);
    }
  }
  return std::nullopt;
}

// The "Depth Units" option (std_msgs/Float32, metres per unit) when the bag has one.
std::optional<double> DepthUnitsPerMetre(const RosBagIndex& index,
                                         io_detail::RosBagReader& reader) {
  for (const RosConnection& c : index.connections) {
    if (c.topic.find("Depth Units") == std::string::npos || c.type != "std_msgs/Float32") continue;
    for (const RosMessageRef& m : index.messages) {
      if (m.connection != c.id || m.size < 4) continue;
      float metres;
      const std::string bytes = reader.Read(m);
      std::memcpy(&metres, bytes.data(), 4);
      if (metres > 0 && std::isfinite(metres)) return 1.0 / metres;
    }
  }
  return std::nullopt;
}

}  // namespace

void RealSenseBagOptions::Validate() const {
  CheckNonNegative("max_time_difference_s", max_time_difference_s);
  if (depth_units_per_m) CheckPositive("depth_units_per_m", *depth_units_per_m);
}

bool IsRosBagFile(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".bag";
}

std::unique_ptr<RgbdSequence> OpenRealSenseBag(const fs::path& path,
                                               const RealSenseBagOptions& options) {
  options.Validate();
  auto owned_index = std::make_unique<RosBagIndex>(io_detail::IndexRosBag(path));
  const RosBagIndex& index = *owned_index;
  io_detail::RosBagReader in(path, index);
  const std::vector<Stream> streams = ImageStreams(index, in, path);
  const Stream* color = nullptr;
  const Stream* depth = nullptr;
  for (const Stream& s : streams) {
    if (!color && Channels(s.encoding) > 0) color = &s;
    if (!depth && IsDepth(s.encoding)) depth = &s;
  }
  if (!color || !depth) {
    std::string found;
    for (const Stream& s : streams)
      found += fmt::format(" {} ({})", s.connection->topic, s.encoding);
    throw InputError(path.string(), "",
                     fmt::format("expected a colour image topic (rgb8, bgr8, rgba8, bgra8) and a "
                                 "depth one (16UC1, mono16); found{}",
                                 found.empty() ? " no image topics" : found));
  }
  const std::optional<CameraIntrinsics> k_color =
      CameraOf(color->connection->topic, index, in, path);
  const std::optional<CameraIntrinsics> k_depth =
      CameraOf(depth->connection->topic, index, in, path);
  if (!k_color || !k_depth) {
    throw InputError(path.string(), color->connection->topic,
                     "expected a sensor_msgs/CameraInfo message for the colour and depth images");
  }
  const auto same = [](const CameraIntrinsics& a, const CameraIntrinsics& b) {
    return a.width == b.width && a.height == b.height && std::abs(a.fx - b.fx) < 1e-3 &&
           std::abs(a.fy - b.fy) < 1e-3 && std::abs(a.cx - b.cx) < 1e-3 &&
           std::abs(a.cy - b.cy) < 1e-3;
  };
  if (!same(*k_color, *k_depth)) {
    throw InputError(
        path.string(), depth->connection->topic,
        fmt::format("expected depth registered to the colour image (the same camera); the depth "
                    "is {}x{} fx {:.1f}, the colour {}x{} fx {:.1f}: record with depth aligned to "
                    "colour (rs.align), or convert to an Open3D folder",
                    k_depth->width, k_depth->height, k_depth->fx, k_color->width, k_color->height,
                    k_color->fx));
  }
  const auto pairs =
      io_detail::AssociateByTime(color->stamps_s, depth->stamps_s, options.max_time_difference_s);
  if (pairs.empty()) {
    throw InputError(path.string(), "",
                     fmt::format("expected colour and depth images within {} s of each other, "
                                 "found none",
                                 options.max_time_difference_s));
  }
  std::vector<std::pair<RosMessageRef, RosMessageRef>> frames;
  std::vector<double> times;
  for (const auto& [i, j] : pairs) {
    frames.emplace_back(color->messages[i], depth->messages[j]);
    times.push_back(color->stamps_s[i]);
  }
  const double units = options.depth_units_per_m ? *options.depth_units_per_m
                                                 : DepthUnitsPerMetre(index, in).value_or(1000.0);
  spdlog::info(
      "{}: colour {} ({}), depth {} ({}): {} of {} colour frames paired; {} depth units "
      "per metre",
      path.string(), color->connection->topic, color->encoding, depth->connection->topic,
      depth->encoding, frames.size(), color->messages.size(), units);
  return std::make_unique<BagSequence>(path, std::move(owned_index), *k_color, units,
                                       std::move(frames), std::move(times));
}

}  // namespace simtree
