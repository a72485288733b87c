#pragma once
// ROS bag version 2.0 (the format of `rosbag record` and of RealSense .bag recordings), read
// without ROS: the records (a header of name=value fields, then data) of the file and of its
// chunks; connections (topic, message type) and where each message's bytes are. Chunks
// compressed with lz4 or bz2 are read when simtree was built with liblz4 / libbz2 (else refused
// with a message).

#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace simtree::io_detail {

struct RosConnection {
  uint32_t id = 0;
  std::string topic;
  std::string type;  // "sensor_msgs/Image"
};

struct RosChunk {
  std::string compression;  // "none", "lz4", "bz2"
  uint64_t offset = 0;      // of its data in the file
  uint32_t size = 0;
  uint32_t uncompressed_size = 0;
};

struct RosMessageRef {
  uint32_t connection = 0;
  uint64_t time_ns = 0;  // the record's time (when it was recorded)
  int chunk = -1;        // the compressed chunk holding it, -1 when its bytes are in the file
  uint64_t offset = 0;   // of the serialized message: in the file, or in the chunk's data
  uint32_t size = 0;
};

struct RosBagIndex {
  std::vector<RosConnection> connections;  // by id, each once
  std::vector<RosMessageRef> messages;     // in file order
  std::vector<RosChunk> chunks;            // the compressed ones
  const RosConnection* FindConnection(uint32_t id) const;
};

// Whether chunks compressed so are read by this build.
bool RosCompressionSupported(const std::string& compression);

// Throws InputError naming the file and the byte offset of a bad record.
RosBagIndex IndexRosBag(const std::filesystem::path& path);

// Reads messages of an indexed bag, keeping the last decompressed chunk.
class RosBagReader {
 public:
  RosBagReader(std::filesystem::path path, const RosBagIndex& index);
  // The serialized bytes of one message; at most `max_bytes` of them when given.
  std::string Read(const RosMessageRef& message, uint32_t max_bytes = UINT32_MAX);

 private:
  std::filesystem::path path_;
  const RosBagIndex& index_;
  std::ifstream in_;
  int cached_chunk_ = -1;
  std::string cached_;
};

// Reads ROS 1 serialization (little-endian; strings and variable arrays with a uint32 length).
class RosReader {
 public:
  RosReader(const std::string& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
  uint8_t U8();
  uint32_t U32();
  double F64();
  std::string String();
  // A uint8[] of `count` bytes (count read first when `count` < 0); returns the bytes.
  std::string Bytes(int64_t count = -1);
  void Skip(size_t n);
  size_t remaining() const { return bytes_.size() - at_; }

 private:
  const char* Take(size_t n);
  const std::string& bytes_;
  std::string what_;
  size_t at_ = 0;
};

}  // namespace simtree::io_detail
