// After the ROS wiki's "Bags/Format/2.0": "#ROSBAG V2.0\n", then records of
// <int32 header_len><header: fields of <int32 len>name=value><int32 data_len><data>, op codes
// 0x02 message data, 0x03 bag header, 0x04 index data, 0x05 chunk, 0x06 chunk info,
// 0x07 connection. A chunk's data holds message-data and connection records.

#include "simtree/io/detail/ros_bag.h"

#include <algorithm>
#include <cstring>
#include <map>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::io_detail {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr uint8_t kMessageData = 0x02, kChunk = 0x05, kConnection = 0x07;

using Fields = std::map<std::string, std::string>;

template <typename T>
T Le(const std::string& bytes, size_t at = 0) {
  T value{};
  std::memcpy(&value, bytes.data() + at, std::min(sizeof(T), bytes.size() - at));
  return value;
}

class BagFile {
 public:
  explicit BagFile(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw IoError(fmt::format("{}: cannot open", path.string()));
    size_ = fs::file_size(path);
  }
  uint64_t size() const { return size_; }
  std::string Read(uint64_t offset, uint64_t n, const char* what) {
    if (offset + n > size_) Fail(offset, fmt::format("{} of {} bytes runs past the end", what, n));
    std::string bytes(n, '\0');
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(bytes.data(), static_cast<std::streamsize>(n));
    if (!in_) Fail(offset, fmt::format("cannot read {}", what));
    return bytes;
  }
  [[noreturn]] void Fail(uint64_t offset, const std::string& message) const {
    throw InputError(path_.string(), fmt::format("byte {}", offset), message);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
  std::ifstream in_;
  uint64_t size_ = 0;
};

Fields ParseFields(const std::string& header, BagFile& file, uint64_t offset) {
  Fields fields;
  for (size_t at = 0; at < header.size();) {
    if (at + 4 > header.size()) file.Fail(offset, "expected a header field's length");
    const uint32_t len = Le<uint32_t>(header, at);
    at += 4;
    if (len > header.size() - at) file.Fail(offset, "a header field runs past its header");
    const std::string field = header.substr(at, len);
    const size_t eq = field.find('=');
    if (eq == std::string::npos) file.Fail(offset, "expected name=value in a record header");
    fields[field.substr(0, eq)] = field.substr(eq + 1);
    at += len;
  }
  return fields;
}

struct Record {
  Fields fields;
  uint64_t data_offset = 0;
  uint32_t data_size = 0;
  uint64_t end = 0;
};

Record ReadRecord(BagFile& file, uint64_t offset, uint64_t limit) {
  Record r;
  if (offset + 4 > limit) file.Fail(offset, "expected a record, the data ends");
  const uint32_t header_len = Le<uint32_t>(file.Read(offset, 4, "a record header length"));
  if (offset + 8 + header_len > limit) file.Fail(offset, "a record header runs past the end");
  r.fields = ParseFields(file.Read(offset + 4, header_len, "a record header"), file, offset);
  const uint64_t data_len_at = offset + 4 + header_len;
  r.data_size = Le<uint32_t>(file.Read(data_len_at, 4, "a record data length"));
  r.data_offset = data_len_at + 4;
  r.end = r.data_offset + r.data_size;
  if (r.end > limit) file.Fail(offset, "a record's data runs past the end (truncated?)");
  return r;
}

std::string Field(const Record& r, const std::string& name, BagFile& file, uint64_t offset) {
  const auto it = r.fields.find(name);
  if (it == r.fields.end()) file.Fail(offset, fmt::format("expected a \"{}\" header field", name));
  return it->second;
}

void AddConnection(const Record& r, BagFile& file, uint64_t offset, RosBagIndex& index) {
  RosConnection c;
  c.id = Le<uint32_t>(Field(r, "conn", file, offset));
  c.topic = Field(r, "topic", file, offset);
  const Fields data = ParseFields(file.Read(r.data_offset, r.data_size, "a connection header"),
                                  file, r.data_offset);
  if (const auto it = data.find("type"); it != data.end()) c.type = it->second;
  if (!index.FindConnection(c.id)) index.connections.push_back(c);
}

void ReadRecords(BagFile& file, uint64_t begin, uint64_t end, bool in_chunk, RosBagIndex& index) {
  for (uint64_t offset = begin; offset < end;) {
    const Record r = ReadRecord(file, offset, end);
    const std::string op = Field(r, "op", file, offset);
    if (op.size() != 1) file.Fail(offset, "expected a one-byte \"op\" field");
    switch (static_cast<uint8_t>(op[0])) {
      case kMessageData: {
        const std::string time = Field(r, "time", file, offset);
        RosMessageRef m;
        m.connection = Le<uint32_t>(Field(r, "conn", file, offset));
        m.time_ns = uint64_t{Le<uint32_t>(time)} * 1000000000ull + Le<uint32_t>(time, 4);
        m.offset = r.data_offset;
        m.size = r.data_size;
        index.messages.push_back(m);
        break;
      }
      case kConnection:
        AddConnection(r, file, offset, index);
        break;
      case kChunk: {
        if (in_chunk) file.Fail(offset, "a chunk inside a chunk");
        const std::string compression = Field(r, "compression", file, offset);
        if (compression != "none") {
          file.Fail(offset, fmt::format("a chunk compressed with {} is not read; write the bag "
                                        "uncompressed (`rosbag decompress`, or record without "
                                        "compression)",
                                        compression));
        }
        ReadRecords(file, r.data_offset, r.end, true, index);
        break;
      }
      default:  // bag header, index data, chunk info: the index this reader rebuilds
        break;
    }
    offset = r.end;
  }
}

}  // namespace

const RosConnection* RosBagIndex::FindConnection(uint32_t id) const {
  for (const RosConnection& c : connections) {
    if (c.id == id) return &c;
  }
  return nullptr;
}

RosBagIndex IndexRosBag(const fs::path& path) {
  BagFile file(path);
  const size_t magic = sizeof(kMagic) - 1;
  if (file.size() < magic || file.Read(0, magic, "the version line") != kMagic) {
    throw InputError(path.string(), "", "expected a ROS bag version 2.0 (\"#ROSBAG V2.0\")");
  }
  RosBagIndex index;
  ReadRecords(file, magic, file.size(), false, index);
  return index;
}

std::string ReadRosMessage(std::ifstream& in, const RosMessageRef& m, const fs::path& path) {
  std::string bytes(m.size, '\0');
  in.seekg(static_cast<std::streamoff>(m.offset));
  if (!in.read(bytes.data(), m.size)) {
    throw InputError(path.string(), fmt::format("byte {}", m.offset), "cannot read the message");
  }
  return bytes;
}

const char* RosReader::Take(size_t n) {
  if (n > bytes_.size() - at_) {
    throw InputError(
        what_, fmt::format("byte {}", at_),
        fmt::format("expected {} more bytes, the message has {}", n, bytes_.size() - at_));
  }
  const char* p = bytes_.data() + at_;
  at_ += n;
  return p;
}

uint8_t RosReader::U8() { return static_cast<uint8_t>(*Take(1)); }
uint32_t RosReader::U32() {
  uint32_t v;
  std::memcpy(&v, Take(4), 4);
  return v;
}
double RosReader::F64() {
  double v;
  std::memcpy(&v, Take(8), 8);
  return v;
}
std::string RosReader::String() { return Bytes(); }
std::string RosReader::Bytes(int64_t count) {
  const size_t n = count < 0 ? U32() : static_cast<size_t>(count);
  const char* p = Take(n);
  return std::string(p, n);
}
void RosReader::Skip(size_t n) { Take(n); }

}  // namespace simtree::io_detail
