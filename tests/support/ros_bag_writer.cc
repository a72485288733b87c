#include "support/ros_bag_writer.h"

#include <cmath>
#include <cstdint>

#ifdef SIMTREE_HAVE_LZ4
#include <lz4frame.h>
#endif
#ifdef SIMTREE_HAVE_BZ2
#include <bzlib.h>
#endif

#include "simtree/core/atomic_file.h"

namespace simtree::test {
namespace {

// ROS 1 serialization.
struct Ser {
  std::string bytes;
  template <typename T>
  Ser& Put(T v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
    return *this;
  }
  Ser& Str(const std::string& s) {
    Put<uint32_t>(static_cast<uint32_t>(s.size()));
    bytes += s;
    return *this;
  }
  Ser& Stamp(double t) {
    Put<uint32_t>(0);
    Put<uint32_t>(static_cast<uint32_t>(t));
    Put<uint32_t>(static_cast<uint32_t>(std::llround((t - static_cast<uint32_t>(t)) * 1e9)));
    return Str("frame");
  }
};

std::string Field(const std::string& name, const std::string& value) {
  Ser s;
  s.Str(name + "=" + value);
  return s.bytes;
}
template <typename T>
std::string Bin(T v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof(T));
}
std::string Record(const std::string& header, const std::string& data) {
  Ser s;
  s.Str(header).Str(data);
  return s.bytes;
}
std::string Connection(uint32_t id, const std::string& topic, const std::string& type) {
  return Record(Field("op", "\x07") + Field("conn", Bin(id)) + Field("topic", topic),
                Field("topic", topic) + Field("type", type) + Field("md5sum", "0"));
}
std::string Message(uint32_t id, double t, const std::string& data) {
  const std::string time = Bin(static_cast<uint32_t>(t)) + Bin(uint32_t{0});
  return Record(Field("op", "\x02") + Field("conn", Bin(id)) + Field("time", time), data);
}

std::string ColorImage(double t, int frame) {
  Ser s;
  s.Stamp(t)
      .Put<uint32_t>(kBagHeight)
      .Put<uint32_t>(kBagWidth)
      .Str("bgr8")
      .Put<uint8_t>(0)
      .Put<uint32_t>(kBagWidth * 3);
  std::string px;
  for (int y = 0; y < kBagHeight; ++y) {
    for (int x = 0; x < kBagWidth; ++x) {
      px += static_cast<char>(frame * 30);
      px += static_cast<char>(y * 20);
      px += static_cast<char>(x * 10);
    }
  }
  s.Str(px);
  return s.bytes;
}
std::string DepthImage16(double t, int width) {
  Ser s;
  s.Stamp(t)
      .Put<uint32_t>(kBagHeight)
      .Put<uint32_t>(width)
      .Str("mono16")
      .Put<uint8_t>(0)
      .Put<uint32_t>(width * 2);
  std::string px;
  for (int y = 0; y < kBagHeight; ++y) {
    for (int x = 0; x < width; ++x) px += Bin(static_cast<uint16_t>(1000 + 7 * x + y));
  }
  s.Str(px);
  return s.bytes;
}
std::string CameraInfo(double fx) {
  Ser s;
  s.Stamp(0).Put<uint32_t>(kBagHeight).Put<uint32_t>(kBagWidth).Str("plumb_bob").Put<uint32_t>(5);
  for (int i = 0; i < 5; ++i) s.Put<double>(0);
  const double k[9] = {fx, 0, 7.5, 0, fx + 1, 5.5, 0, 0, 1};
  for (double v : k) s.Put<double>(v);
  for (int i = 0; i < 9 + 12; ++i) s.Put<double>(0);  // R, P
  s.Put<uint32_t>(0).Put<uint32_t>(0);                // binning
  for (int i = 0; i < 4; ++i) s.Put<uint32_t>(0);     // roi
  s.Put<uint8_t>(0);
  return s.bytes;
}

// The chunk's data as `compression` stores it.
std::string Compress(const std::string& data, const std::string& compression) {
#ifdef SIMTREE_HAVE_LZ4
  if (compression == "lz4") {
    std::string out(LZ4F_compressFrameBound(data.size(), nullptr), '\0');
    out.resize(LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), nullptr));
    return out;
  }
#endif
#ifdef SIMTREE_HAVE_BZ2
  if (compression == "bz2") {
    std::string in = data;
    unsigned int length = static_cast<unsigned int>(data.size() + data.size() / 100 + 600);
    std::string out(length, '\0');
    BZ2_bzBuffToBuffCompress(out.data(), &length, in.data(), static_cast<unsigned int>(in.size()),
                             9, 0, 0);
    out.resize(length);
    return out;
  }
#endif
  if (compression == "broken") return std::string(data.size() / 2, 'x');
  return data;
}

}  // namespace

bool BagCompressionWritten(const std::string& compression) {
#ifdef SIMTREE_HAVE_LZ4
  if (compression == "lz4") return true;
#endif
#ifdef SIMTREE_HAVE_BZ2
  if (compression == "bz2") return true;
#endif
  return compression == "none" || compression == "broken";
}

std::string BagBytes(const BagSpec& spec) {
  std::string chunk;
  chunk += Connection(0, "/device_0/sensor_1/Color_0/image/data", "sensor_msgs/Image");
  chunk += Connection(1, "/device_0/sensor_0/Depth_0/image/data", "sensor_msgs/Image");
  chunk += Connection(2, "/device_0/sensor_1/Color_0/info/camera_info", "sensor_msgs/CameraInfo");
  chunk += Connection(3, "/device_0/sensor_0/Depth_0/info/camera_info", "sensor_msgs/CameraInfo");
  chunk += Connection(4, "/device_0/sensor_0/option/Depth Units/value", "std_msgs/Float32");
  chunk += Message(2, 1, CameraInfo(14));
  chunk += Message(3, 1, CameraInfo(spec.depth_fx));
  chunk += Message(4, 1, Bin(0.0001f));
  // Depth written before colour, out of order, as bags may interleave them.
  chunk += Message(1, 1, DepthImage16(1.035, spec.depth_width));
  chunk += Message(1, 1, DepthImage16(1.002, spec.depth_width));
  chunk += Message(1, 1, DepthImage16(1.300, spec.depth_width));
  for (int i = 0; i < 3; ++i) chunk += Message(0, 1, ColorImage(1.0 + 0.033 * i, i));
  std::string bag = "#ROSBAG V2.0\n";
  bag += Record(Field("op", "\x03") + Field("index_pos", Bin(uint64_t{0})) +
                    Field("conn_count", Bin(uint32_t{5})) + Field("chunk_count", Bin(uint32_t{1})),
                std::string(64, ' '));
  const std::string compression = spec.compression == "broken" ? "bz2" : spec.compression;
  bag += Record(Field("op", "\x05") + Field("compression", compression) +
                    Field("size", Bin(static_cast<uint32_t>(chunk.size()))),
                Compress(chunk, spec.compression));
  // The index section repeats the connections after the chunks.
  bag += Connection(0, "/device_0/sensor_1/Color_0/image/data", "sensor_msgs/Image");
  return bag;
}

std::filesystem::path WriteBag(const std::filesystem::path& path, const BagSpec& spec) {
  WriteFileAtomically(path, BagBytes(spec));
  return path;
}

}  // namespace simtree::test
