// After the ROS wiki's "Bags/Format/2.0": "#ROSBAG V2.0\n", then records of
// <int32 header_len><header: fields of <int32 len>name=value><int32 data_len><data>, op codes
// 0x02 message data, 0x03 bag header, 0x04 index data, 0x05 chunk, 0x06 chunk info,
// 0x07 connection. A chunk's data (compressed as its "compression" field says, "size" bytes
// uncompressed) holds message-data and connection records.

#include "simtree/io/detail/ros_bag.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <memory>

#include <fmt/format.h>

#ifdef SIMTREE_HAVE_LZ4
#include <lz4frame.h>
#endif
#ifdef SIMTREE_HAVE_BZ2
#include <bzlib.h>
#endif

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
  if (at < bytes.size())
    std::memcpy(&value, bytes.data() + at, std::min(sizeof(T), bytes.size() - at));
  return value;
}

// Where records are read from: the file, or a chunk's decompressed data.
class Source {
 public:
  virtual ~Source() = default;
  virtual uint64_t size() const = 0;
  virtual std::string Read(uint64_t offset, uint64_t n, const char* what) = 0;
  [[noreturn]] virtual void Fail(uint64_t offset, const std::string& message) const = 0;
};

class FileSource : public Source {
 public:
  explicit FileSource(const fs::path& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw IoError(fmt::format("{}: cannot open", path.string()));
    size_ = fs::file_size(path);
  }
  uint64_t size() const override { return size_; }
  std::string Read(uint64_t offset, uint64_t n, const char* what) override {
    if (offset + n > size_) Fail(offset, fmt::format("{} of {} bytes runs past the end", what, n));
    std::string bytes(n, '\0');
    in_.seekg(static_cast<std::streamoff>(offset));
    in_.read(bytes.data(), static_cast<std::streamsize>(n));
    if (!in_) Fail(offset, fmt::format("cannot read {}", what));
    return bytes;
  }
  [[noreturn]] void Fail(uint64_t offset, const std::string& message) const override {
    throw InputError(path_.string(), fmt::format("byte {}", offset), message);
  }

 private:
  fs::path path_;
  std::ifstream in_;
  uint64_t size_ = 0;
};

class ChunkSource : public Source {
 public:
  ChunkSource(std::string data, const fs::path& path, uint64_t chunk_offset)
      : data_(std::move(data)), path_(path), chunk_offset_(chunk_offset) {}
  uint64_t size() const override { return data_.size(); }
  std::string Read(uint64_t offset, uint64_t n, const char* what) override {
    if (offset + n > data_.size()) {
      Fail(offset, fmt::format("{} of {} bytes runs past the end", what, n));
    }
    return data_.substr(offset, n);
  }
  [[noreturn]] void Fail(uint64_t offset, const std::string& message) const override {
    throw InputError(path_.string(),
                     fmt::format("byte {} of the chunk at byte {}", offset, chunk_offset_),
                     message);
  }

 private:
  std::string data_;
  fs::path path_;
  uint64_t chunk_offset_;
};

[[noreturn]] void ChunkFail(const RosChunk& chunk, const fs::path& path, const std::string& why) {
  throw InputError(path.string(),
                   fmt::format("the {} chunk at byte {}", chunk.compression, chunk.offset), why);
}

// The most a chunk may hold uncompressed. rosbag writes chunks of 768 KiB (a larger message gets
// one of its own: a 1920x1080 colour image is 6 MB). The size field is allocated before
// decompressing, so a damaged one must be refused, not become a 4 GB allocation.
constexpr uint32_t kMaxChunkBytes = 256u << 20;

std::string Decompress(const RosChunk& chunk, const std::string& compressed, const fs::path& path) {
  if (chunk.compression == "none") return compressed;
  const auto fail = [&](const std::string& why) { ChunkFail(chunk, path, why); };
  if (chunk.uncompressed_size > kMaxChunkBytes) {
    fail(fmt::format("size: expected at most {} bytes uncompressed, the header claims {}",
                     kMaxChunkBytes, chunk.uncompressed_size));
  }
  std::string out(chunk.uncompressed_size, '\0');
#ifdef SIMTREE_HAVE_LZ4
  if (chunk.compression == "lz4") {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) fail("no lz4 context");
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> guard(
        ctx, LZ4F_freeDecompressionContext);
    size_t written = 0, read = 0;
    while (read < compressed.size()) {
      size_t dst = out.size() - written, src = compressed.size() - read;
      const size_t r =
          LZ4F_decompress(ctx, out.data() + written, &dst, compressed.data() + read, &src, nullptr);
      if (LZ4F_isError(r)) fail(fmt::format("lz4: {}", LZ4F_getErrorName(r)));
      written += dst;
      read += src;
      if (r == 0) break;
      if (dst == 0 && src == 0) fail("lz4: the data ends inside a frame");
    }
    if (written != out.size()) {
      fail(fmt::format("expected {} bytes uncompressed, got {}", out.size(), written));
    }
    return out;
  }
#endif
#ifdef SIMTREE_HAVE_BZ2
  if (chunk.compression == "bz2") {
    unsigned int length = static_cast<unsigned int>(out.size());
    std::string in = compressed;
    const int r = BZ2_bzBuffToBuffDecompress(out.data(), &length, in.data(),
                                             static_cast<unsigned int>(in.size()), 0, 0);
    if (r != BZ_OK || length != out.size()) {
      fail(fmt::format("bz2: error {} ({} of {} bytes)", r, length, out.size()));
    }
    return out;
  }
#endif
  ChunkFail(chunk, path,
            "not read by this build (built without its library); decompress the bag first "
            "(`rosbag decompress`)");
}

Fields ParseFields(const std::string& header, Source& source, uint64_t offset) {
  Fields fields;
  for (size_t at = 0; at < header.size();) {
    if (at + 4 > header.size()) source.Fail(offset, "expected a header field's length");
    const uint32_t len = Le<uint32_t>(header, at);
    at += 4;
    if (len > header.size() - at) source.Fail(offset, "a header field runs past its header");
    const std::string field = header.substr(at, len);
    const size_t eq = field.find('=');
    if (eq == std::string::npos) source.Fail(offset, "expected name=value in a record header");
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

Record ReadRecord(Source& source, uint64_t offset) {
  Record r;
  const uint64_t limit = source.size();
  if (offset + 4 > limit) source.Fail(offset, "expected a record, the data ends");
  const uint32_t header_len = Le<uint32_t>(source.Read(offset, 4, "a record header length"));
  if (offset + 8 + header_len > limit) source.Fail(offset, "a record header runs past the end");
  r.fields = ParseFields(source.Read(offset + 4, header_len, "a record header"), source, offset);
  const uint64_t data_len_at = offset + 4 + header_len;
  r.data_size = Le<uint32_t>(source.Read(data_len_at, 4, "a record data length"));
  r.data_offset = data_len_at + 4;
  r.end = r.data_offset + r.data_size;
  if (r.end > limit) source.Fail(offset, "a record's data runs past the end (truncated?)");
  return r;
}

std::string Field(const Record& r, const std::string& name, Source& source, uint64_t offset) {
  const auto it = r.fields.find(name);
  if (it == r.fields.end()) {
    source.Fail(offset, fmt::format("expected a \"{}\" header field", name));
  }
  return it->second;
}

void AddConnection(const Record& r, Source& source, uint64_t offset, RosBagIndex& index) {
  RosConnection c;
  c.id = Le<uint32_t>(Field(r, "conn", source, offset));
  c.topic = Field(r, "topic", source, offset);
  const Fields data = ParseFields(source.Read(r.data_offset, r.data_size, "a connection header"),
                                  source, r.data_offset);
  if (const auto it = data.find("type"); it != data.end()) c.type = it->second;
  if (!index.FindConnection(c.id)) index.connections.push_back(c);
}

// `chunk`: the index of the compressed chunk `source` holds, -1 for the file or an uncompressed
// chunk (whose records are read in place).
void ReadRecords(Source& source, uint64_t begin, uint64_t end, int chunk, bool in_chunk,
                 const fs::path& path, RosBagIndex& index) {
  for (uint64_t offset = begin; offset < end;) {
    const Record r = ReadRecord(source, offset);
    const std::string op = Field(r, "op", source, offset);
    if (op.size() != 1) source.Fail(offset, "expected a one-byte \"op\" field");
    switch (static_cast<uint8_t>(op[0])) {
      case kMessageData: {
        const std::string time = Field(r, "time", source, offset);
        RosMessageRef m;
        m.connection = Le<uint32_t>(Field(r, "conn", source, offset));
        m.time_ns = uint64_t{Le<uint32_t>(time)} * 1000000000ull + Le<uint32_t>(time, 4);
        m.chunk = chunk;
        m.offset = r.data_offset;
        m.size = r.data_size;
        index.messages.push_back(m);
        break;
      }
      case kConnection:
        AddConnection(r, source, offset, index);
        break;
      case kChunk: {
        if (in_chunk) source.Fail(offset, "a chunk inside a chunk");
        RosChunk c;
        c.compression = Field(r, "compression", source, offset);
        c.uncompressed_size = Le<uint32_t>(Field(r, "size", source, offset));
        c.offset = r.data_offset;
        c.size = r.data_size;
        if (c.compression == "none") {
          ReadRecords(source, r.data_offset, r.end, -1, true, path, index);
          break;
        }
        if (!RosCompressionSupported(c.compression)) {
          source.Fail(offset, fmt::format("a chunk compressed with {} is not read by this build; "
                                          "decompress the bag first (`rosbag decompress`)",
                                          c.compression));
        }
        ChunkSource data(Decompress(c, source.Read(c.offset, c.size, "a chunk"), path), path,
                         c.offset);
        index.chunks.push_back(c);
        ReadRecords(data, 0, data.size(), static_cast<int>(index.chunks.size() - 1), true, path,
                    index);
        break;
      }
      default:  // bag header, index data, chunk info: the index this reader rebuilds
        break;
    }
    offset = r.end;
  }
}

}  // namespace

bool RosCompressionSupported(const std::string& compression) {
  if (compression == "none") return true;
#ifdef SIMTREE_HAVE_LZ4
  if (compression == "lz4") return true;
#endif
#ifdef SIMTREE_HAVE_BZ2
  if (compression == "bz2") return true;
#endif
  return false;
}

const RosConnection* RosBagIndex::FindConnection(uint32_t id) const {
  for (const RosConnection& c : connections) {
    if (c.id == id) return &c;
  }
  return nullptr;
}

RosBagIndex IndexRosBag(const fs::path& path) {
  FileSource file(path);
  const size_t magic = sizeof(kMagic) - 1;
  if (file.size() < magic || file.Read(0, magic, "the version line") != kMagic) {
    throw InputError(path.string(), "", "expected a ROS bag version 2.0 (\"#ROSBAG V2.0\")");
  }
  RosBagIndex index;
  ReadRecords(file, magic, file.size(), -1, false, path, index);
  return index;
}

RosBagReader::RosBagReader(fs::path path, const RosBagIndex& index)
    : path_(std::move(path)), index_(index), in_(path_, std::ios::binary) {
  if (!in_) throw IoError(fmt::format("{}: cannot open", path_.string()));
}

std::string RosBagReader::Read(const RosMessageRef& m, uint32_t max_bytes) {
  const uint32_t n = std::min(m.size, max_bytes);
  if (m.chunk < 0) {
    std::string bytes(n, '\0');
    in_.seekg(static_cast<std::streamoff>(m.offset));
    if (!in_.read(bytes.data(), n)) {
      throw InputError(path_.string(), fmt::format("byte {}", m.offset), "cannot read the message");
    }
    return bytes;
  }
  if (m.chunk != cached_chunk_) {
    const RosChunk& c = index_.chunks.at(static_cast<size_t>(m.chunk));
    std::string compressed(c.size, '\0');
    in_.seekg(static_cast<std::streamoff>(c.offset));
    if (!in_.read(compressed.data(), c.size)) {
      throw InputError(path_.string(), fmt::format("byte {}", c.offset), "cannot read the chunk");
    }
    cached_ = Decompress(c, compressed, path_);
    cached_chunk_ = m.chunk;
  }
  return cached_.substr(m.offset, n);
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
