// libavformat behind MkvDemuxer. The recording's streams are read straight from the Matroska
// headers (no probing decode: the IMU track has no codec libav knows).

#include "simtree/io/detail/mkv_demuxer.h"

#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include <fmt/format.h>

extern "C" {
#include <libavformat/avformat.h>
#include <libavutil/error.h>
}

#include "simtree/core/error.h"

namespace simtree::azure_detail {
namespace {

std::string AvError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return text;
}

std::string Metadata(const AVDictionary* dictionary, const char* key) {
  const AVDictionaryEntry* entry = av_dict_get(dictionary, key, nullptr, 0);
  return entry ? entry->value : "";
}

std::string FourCc(uint32_t tag) {
  if (tag == 0) return "";
  std::string out;
  for (int i = 0; i < 4; ++i) out += static_cast<char>((tag >> (8 * i)) & 0xff);
  return out;
}

// The track's K4A_<name>_MODE tag.
std::string ModeTag(const AVStream* stream, const std::string& name) {
  return Metadata(stream->metadata, ("K4A_" + name + "_MODE").c_str());
}

// An EBML variable-length integer at `in`'s position (an element ID keeps its length marker);
// nothing at the end of the file. `unknown` is set when every value bit is 1 (size unknown).
std::optional<uint64_t> ReadVint(std::istream& in, bool keep_marker, bool* unknown = nullptr) {
  const int first = in.get();
  if (first == EOF || first == 0) return std::nullopt;
  int length = 1;
  while (!(first & (0x80 >> (length - 1)))) ++length;
  uint64_t value = keep_marker ? first : first & (0xff >> length);
  bool all_ones = value == (0xffu >> length);
  for (int i = 1; i < length; ++i) {
    const int byte = in.get();
    if (byte == EOF) return std::nullopt;
    value = (value << 8) | static_cast<uint64_t>(byte);
    all_ones = all_ones && byte == 0xff;
  }
  if (unknown) *unknown = all_ones;
  return value;
}

// libavformat reads a cut file to its last whole packet and reports a clean end, so a truncated
// recording is found here: the Segment element's size (which k4arecorder writes when it closes
// the file) must fit in the file.
void CheckNotTruncated(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::optional<uint64_t> ebml_id = ReadVint(in, true);
  const std::optional<uint64_t> ebml_size = ReadVint(in, false);
  if (ebml_id != 0x1A45DFA3u || !ebml_size) return;  // not Matroska: libav says so
  in.seekg(static_cast<std::streamoff>(*ebml_size), std::ios::cur);
  const std::optional<uint64_t> segment_id = ReadVint(in, true);
  bool unknown = false;
  const std::optional<uint64_t> segment_size = ReadVint(in, false, &unknown);
  const uint64_t file_size = std::filesystem::file_size(path);
  if (!segment_id || !segment_size) {
    throw InputError(path.string(), "",
                     fmt::format("the file ends inside its Matroska header ({} bytes): expected "
                                 "a whole recording (truncated file?)",
                                 file_size));
  }
  if (*segment_id != 0x18538067u || unknown) return;  // a layout libav judges alone
  const uint64_t end = static_cast<uint64_t>(in.tellg()) + *segment_size;
  if (end > file_size) {
    throw InputError(path.string(), "",
                     fmt::format("expected {} bytes (its Matroska segment's size), the file has "
                                 "{}: truncated (copy or recording cut short?)",
                                 end, file_size));
  }
}

}  // namespace

struct MkvDemuxer::Impl {
  std::string source;
  AVFormatContext* format = nullptr;
  AVPacket* packet = nullptr;
  ~Impl() {
    av_packet_free(&packet);
    avformat_close_input(&format);
  }
};

MkvDemuxer::MkvDemuxer(const std::filesystem::path& path) : impl_(std::make_unique<Impl>()) {
  impl_->source = path.string();
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(impl_->source, "", "expected an Azure Kinect recording (.mkv), no such file");
  }
  av_log_set_level(AV_LOG_FATAL);  // libav's warnings on the IMU track are noise; errors are ours
  CheckNotTruncated(path);
  const int opened = avformat_open_input(&impl_->format, impl_->source.c_str(), nullptr, nullptr);
  if (opened < 0) {
    throw InputError(impl_->source, "",
                     fmt::format("expected a Matroska (.mkv) recording, libav cannot open it: {}",
                                 AvError(opened)));
  }
  impl_->packet = av_packet_alloc();
  for (unsigned i = 0; i < impl_->format->nb_streams; ++i) {
    const AVStream* stream = impl_->format->streams[i];
    if (stream->codecpar->codec_type == AVMEDIA_TYPE_ATTACHMENT) continue;
    MkvStream s;
    s.index = static_cast<int>(i);
    s.track.name = Metadata(stream->metadata, "title");
    s.track.codec = avcodec_get_name(stream->codecpar->codec_id);
    s.track.fourcc = FourCc(stream->codecpar->codec_tag);
    s.track.mode = ModeTag(stream, s.track.name);
    s.track.width = stream->codecpar->width;
    s.track.height = stream->codecpar->height;
    s.parameters = stream->codecpar;
    streams_.push_back(s);
  }
}

MkvDemuxer::~MkvDemuxer() = default;

std::optional<std::string> MkvDemuxer::Attachment(const std::string& filename) const {
  for (unsigned i = 0; i < impl_->format->nb_streams; ++i) {
    const AVStream* stream = impl_->format->streams[i];
    if (stream->codecpar->codec_type != AVMEDIA_TYPE_ATTACHMENT) continue;
    if (Metadata(stream->metadata, "filename") != filename) continue;
    const AVCodecParameters* p = stream->codecpar;
    return std::string(reinterpret_cast<const char*>(p->extradata),
                       p->extradata ? static_cast<size_t>(p->extradata_size) : 0);
  }
  return std::nullopt;
}

std::string MkvDemuxer::Tag(const std::string& key) const {
  return Metadata(impl_->format->metadata, key.c_str());
}

void MkvDemuxer::Select(const std::vector<int>& stream_indices) {
  for (unsigned i = 0; i < impl_->format->nb_streams; ++i) {
    impl_->format->streams[i]->discard = AVDISCARD_ALL;
  }
  for (int index : stream_indices) impl_->format->streams[index]->discard = AVDISCARD_DEFAULT;
}

bool MkvDemuxer::Next(MkvPacket& packet) {
  av_packet_unref(impl_->packet);
  for (;;) {
    const int read = av_read_frame(impl_->format, impl_->packet);
    if (read == AVERROR_EOF) return false;
    if (read < 0) {
      throw InputError(impl_->source, "",
                       fmt::format("the recording cannot be read past this point (truncated or "
                                   "corrupt file?): {}",
                                   AvError(read)));
    }
    const AVStream* stream = impl_->format->streams[impl_->packet->stream_index];
    if (stream->discard == AVDISCARD_ALL) {
      av_packet_unref(impl_->packet);
      continue;
    }
    const int64_t pts =
        impl_->packet->pts != AV_NOPTS_VALUE ? impl_->packet->pts : impl_->packet->dts;
    packet.stream = impl_->packet->stream_index;
    packet.timestamp_us = av_rescale_q(pts, stream->time_base, AVRational{1, 1000000});
    packet.data = impl_->packet->data;
    packet.size = impl_->packet->size;
    return true;
  }
}

}  // namespace simtree::azure_detail
