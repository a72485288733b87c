// AzureKinectReader: the recording's tracks and calibration at open, then one capture per Next()
// (demux a packet, decode it, hand it to the pairer until a capture closes).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/azure_kinect.h"
#include "simtree/io/detail/azure_frame_decoder.h"
#include "simtree/io/detail/capture_pairer.h"
#include "simtree/io/detail/mkv_demuxer.h"
#include "simtree/io/detail/track_clock.h"

namespace simtree {
namespace {

using azure_detail::MkvStream;

constexpr const char* kCalibrationAttachment = "calibration.json";

std::string TrackList(const std::vector<MkvStream>& streams) {
  std::string out;
  for (const MkvStream& s : streams) out += (out.empty() ? "" : ", ") + s.track.name;
  return out.empty() ? "none" : out;
}

const MkvStream* FindStream(const std::vector<MkvStream>& streams, const std::string& name) {
  for (const MkvStream& s : streams) {
    if (s.track.name == name) return &s;
  }
  return nullptr;
}

// A track the options ask for: present, and for DEPTH and IR 16-bit raw (`b16g`).
const MkvStream* RequireTrack(const std::vector<MkvStream>& streams, const std::string& name,
                              bool wanted, const std::string& source) {
  if (!wanted) return nullptr;
  const MkvStream* s = FindStream(streams, name);
  if (!s) {
    throw InputError(source, name + " track",
                     fmt::format("expected a {} track (recorded with that camera on), the file "
                                 "has: {}",
                                 name, TrackList(streams)));
  }
  if (name != "COLOR" && (s->track.codec != "rawvideo" || s->track.fourcc != "b16g")) {
    throw InputError(source, name + " track",
                     fmt::format("expected raw 16-bit frames (FourCC b16g), got codec {} FourCC "
                                 "'{}'",
                                 s->track.codec, s->track.fourcc));
  }
  if (s->track.width <= 0 || s->track.height <= 0) {
    throw InputError(source, name + " track", "expected a positive image size in its header");
  }
  return s;
}

int64_t ParseNanosecondsAsUs(const std::string& tag) {
  if (tag.empty()) return 0;
  try {
    return std::stoll(tag) / 1000;
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace

void AzureReaderOptions::Validate() const {
  CheckOption(read_color || read_depth || read_ir, "reader options", "read_color",
              "expected at least one of colour, depth and IR to be read");
  CheckAtLeast("pair_tolerance_us", pair_tolerance_us, int64_t{0});
}

struct AzureKinectReader::Impl {
  std::filesystem::path path;
  std::string source;
  AzureReaderOptions options;
  azure_detail::MkvDemuxer demuxer;
  std::vector<AzureTrack> tracks;
  AzureCalibration calibration;
  std::string calibration_json;
  int64_t depth_delay_us = 0;
  int64_t start_offset_us = 0;
  const MkvStream* color = nullptr;
  const MkvStream* depth = nullptr;
  const MkvStream* ir = nullptr;
  std::unique_ptr<azure_detail::ColorDecoder> color_decoder;
  azure_detail::TrackClock color_clock, depth_clock, ir_clock;
  std::unique_ptr<azure_detail::CapturePairer> pairer;
  AzureReadStats stats;
  bool finished = false;

  Impl(const std::filesystem::path& p, const AzureReaderOptions& o)
      : path(p),
        source(p.string()),
        options(o),
        demuxer(p),
        color_clock(source, "COLOR"),
        depth_clock(source, "DEPTH"),
        ir_clock(source, "IR") {}

  void OpenTracks() {
    const std::vector<MkvStream>& streams = demuxer.streams();
    for (const MkvStream& s : streams) tracks.push_back(s.track);
    color = RequireTrack(streams, "COLOR", options.read_color, source);
    depth = RequireTrack(streams, "DEPTH", options.read_depth, source);
    ir = RequireTrack(streams, "IR", options.read_ir, source);
    if (color) color_decoder = std::make_unique<azure_detail::ColorDecoder>(*color, source);
    std::vector<int> selected;
    for (const MkvStream* s : {color, depth, ir}) {
      if (s) selected.push_back(s->index);
    }
    demuxer.Select(selected);
    depth_delay_us = ParseNanosecondsAsUs(demuxer.Tag("K4A_DEPTH_DELAY_NS"));
    start_offset_us = ParseNanosecondsAsUs(demuxer.Tag("K4A_START_OFFSET_NS"));
    pairer =
        std::make_unique<azure_detail::CapturePairer>(options.pair_tolerance_us, depth_delay_us);
  }

  void ReadCalibration() {
    const std::optional<std::string> json = demuxer.Attachment(kCalibrationAttachment);
    if (!json) {
      throw InputError(source, "calibration.json attachment",
                       "expected the factory calibration that k4arecorder attaches; the file has "
                       "none (was it re-muxed by another tool?)");
    }
    calibration_json = *json;
    const MkvStream* depth_like = FindStream(demuxer.streams(), "DEPTH");
    if (!depth_like) depth_like = FindStream(demuxer.streams(), "IR");
    const MkvStream* color_track = FindStream(demuxer.streams(), "COLOR");
    calibration = ParseAzureCalibration(
        calibration_json, source + " (calibration.json attachment)",
        depth_like ? depth_like->track.width : 0, depth_like ? depth_like->track.height : 0,
        color_track ? color_track->track.width : 0, color_track ? color_track->track.height : 0);
  }

  // Decodes the packet and gives it to the pairer; the capture it closed, if any.
  std::optional<AzureCapture> Consume(const azure_detail::MkvPacket& packet) {
    if (color && packet.stream == color->index) {
      const int frame = color_clock.frames();
      color_clock.Add(packet.timestamp_us);
      return pairer->AddColor(packet.timestamp_us,
                              color_decoder->Decode(packet.data, packet.size, frame));
    }
    if (depth && packet.stream == depth->index) {
      const int frame = depth_clock.frames();
      depth_clock.Add(packet.timestamp_us);
      return pairer->AddDepth(
          packet.timestamp_us,
          azure_detail::DecodeB16g(packet.data, packet.size, depth->track, source, frame));
    }
    const int frame = ir_clock.frames();
    ir_clock.Add(packet.timestamp_us);
    return pairer->AddIr(packet.timestamp_us, azure_detail::DecodeB16g(packet.data, packet.size,
                                                                       ir->track, source, frame));
  }

  AzureCapture Count(AzureCapture capture) {
    ++stats.captures;
    if (color && depth && capture.color && !capture.depth) ++stats.color_without_depth;
    if (color && depth && capture.depth && !capture.color) ++stats.depth_without_color;
    return capture;
  }

  void Finish() {
    finished = true;
    stats.color_frames = color_clock.frames();
    stats.depth_frames = depth_clock.frames();
    stats.ir_frames = ir_clock.frames();
    stats.dropped_color = color_clock.DroppedFrames();
    stats.dropped_depth = depth_clock.DroppedFrames();
    const int64_t period = depth   ? depth_clock.MedianPeriodUs()
                           : color ? color_clock.MedianPeriodUs()
                                   : 0;
    stats.frame_rate_hz = period > 0 ? 1e6 / static_cast<double>(period) : 0.0;
  }
};

AzureKinectReader::AzureKinectReader(const std::filesystem::path& path,
                                     AzureReaderOptions options) {
  options.Validate();
  impl_ = std::make_unique<Impl>(path, options);
  impl_->OpenTracks();
  impl_->ReadCalibration();
}

AzureKinectReader::~AzureKinectReader() = default;

const std::filesystem::path& AzureKinectReader::path() const { return impl_->path; }
const std::vector<AzureTrack>& AzureKinectReader::tracks() const { return impl_->tracks; }
const AzureCalibration& AzureKinectReader::calibration() const { return impl_->calibration; }
const std::string& AzureKinectReader::calibration_json() const { return impl_->calibration_json; }
int64_t AzureKinectReader::depth_delay_us() const { return impl_->depth_delay_us; }
int64_t AzureKinectReader::start_offset_us() const { return impl_->start_offset_us; }
const AzureReadStats& AzureKinectReader::stats() const { return impl_->stats; }

const AzureTrack* AzureKinectReader::FindTrack(const std::string& name) const {
  for (const AzureTrack& t : impl_->tracks) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

std::optional<AzureCapture> AzureKinectReader::Next() {
  if (impl_->finished) return std::nullopt;
  azure_detail::MkvPacket packet;
  while (impl_->demuxer.Next(packet)) {
    if (std::optional<AzureCapture> closed = impl_->Consume(packet)) {
      return impl_->Count(std::move(*closed));
    }
  }
  std::optional<AzureCapture> last = impl_->pairer->Flush();
  impl_->Finish();
  if (last) return impl_->Count(std::move(*last));  // stats are final once this returns
  return std::nullopt;
}

}  // namespace simtree
