// AzureKinectWriter: libavformat's Matroska muxer with raw VFW tracks allowed (so DEPTH keeps its
// b16g FourCC as in k4arecorder's files), libavcodec's MJPEG encoder and libswscale for colour.

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/azure_kinect.h"

namespace simtree {
namespace {

uint32_t Tag(const char* fourcc) {
  return static_cast<uint32_t>(fourcc[0]) | static_cast<uint32_t>(fourcc[1]) << 8 |
         static_cast<uint32_t>(fourcc[2]) << 16 | static_cast<uint32_t>(fourcc[3]) << 24;
}

AVPixelFormat RawColorFormat(AzureColorFormat format) {
  switch (format) {
    case AzureColorFormat::kNv12:
      return AV_PIX_FMT_NV12;
    case AzureColorFormat::kYuy2:
      return AV_PIX_FMT_YUYV422;
    case AzureColorFormat::kBgra:
      return AV_PIX_FMT_BGRA;
    case AzureColorFormat::kMjpeg:
      break;
  }
  return AV_PIX_FMT_YUVJ422P;
}

const char* ColorFourCc(AzureColorFormat format) {
  switch (format) {
    case AzureColorFormat::kNv12:
      return "NV12";
    case AzureColorFormat::kYuy2:
      return "YUY2";
    case AzureColorFormat::kBgra:
      return "BGRA";
    case AzureColorFormat::kMjpeg:
      break;
  }
  return "MJPG";
}

std::string ColorMode(const AzureWriterOptions& o) {
  return fmt::format(
      "{}_{}P", o.color_format == AzureColorFormat::kMjpeg ? "MJPG" : ColorFourCc(o.color_format),
      o.color_height);
}

std::string DepthMode(int width, int height) {
  if (width == 640 && height == 576) return "NFOV_UNBINNED";
  if (width == 320 && height == 288) return "NFOV_2X2BINNED";
  if (width == 512 && height == 512) return "WFOV_2X2BINNED";
  return "WFOV_UNBINNED";
}

}  // namespace

void AzureWriterOptions::Validate() const {
  CheckOption(color_width > 0 || depth_width > 0, "writer options", "color_width",
              "expected a COLOR or a DEPTH track");
  CheckAtLeast("color_width", color_width, 0);
  CheckAtLeast("color_height", color_height, 0);
  CheckAtLeast("depth_width", depth_width, 0);
  CheckAtLeast("depth_height", depth_height, 0);
  CheckOption(color_width % 2 == 0 && color_height % 2 == 0, "writer options", "color_width",
              "expected even colour sizes (NV12 and YUY2 subsample chroma by 2)");
  CheckOption(!ir || depth_width > 0, "writer options", "ir", "expected a depth size for IR");
}

struct AzureKinectWriter::Impl {
  std::filesystem::path target;
  std::filesystem::path temporary;
  AzureWriterOptions options;
  AVFormatContext* format = nullptr;
  AVStream* color = nullptr;
  AVStream* depth = nullptr;
  AVStream* ir = nullptr;
  AVCodecContext* encoder = nullptr;
  SwsContext* scaler = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  bool header_written = false;
  bool closed = false;

  ~Impl() {
    if (format && !closed) {
      if (header_written) av_write_trailer(format);
      avio_closep(&format->pb);
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
    }
    avformat_free_context(format);
    avcodec_free_context(&encoder);
    sws_freeContext(scaler);
    av_frame_free(&frame);
    av_packet_free(&packet);
  }

  [[noreturn]] void Fail(const std::string& what) const {
    throw IoError(fmt::format("{}: cannot write the recording: {}", target.string(), what));
  }

  AVStream* AddVideo(const char* name, AVCodecID codec, uint32_t tag, int width, int height,
                     const std::string& mode_key, const std::string& mode) {
    AVStream* s = avformat_new_stream(format, nullptr);
    s->codecpar->codec_type = AVMEDIA_TYPE_VIDEO;
    s->codecpar->codec_id = codec;
    s->codecpar->codec_tag = tag;
    s->codecpar->width = width;
    s->codecpar->height = height;
    s->time_base = AVRational{1, 1000000};
    av_dict_set(&s->metadata, "title", name, 0);
    av_dict_set(&s->metadata, mode_key.c_str(), mode.c_str(), 0);
    return s;
  }

  void OpenEncoder() {
    const AVCodec* mjpeg = avcodec_find_encoder(AV_CODEC_ID_MJPEG);
    if (!mjpeg) Fail("libav has no MJPEG encoder");
    encoder = avcodec_alloc_context3(mjpeg);
    encoder->width = options.color_width;
    encoder->height = options.color_height;
    encoder->pix_fmt = AV_PIX_FMT_YUVJ422P;
    encoder->time_base = AVRational{1, 1000000};
    encoder->flags |= AV_CODEC_FLAG_QSCALE;
    encoder->global_quality = FF_QP2LAMBDA * 2;  // near-lossless: tests compare pixels
    if (avcodec_open2(encoder, mjpeg, nullptr) < 0) Fail("the MJPEG encoder does not open");
  }

  void AddStreams() {
    const AzureWriterOptions& o = options;
    if (o.color_width > 0) {
      const bool mjpeg = o.color_format == AzureColorFormat::kMjpeg;
      color = AddVideo("COLOR", mjpeg ? AV_CODEC_ID_MJPEG : AV_CODEC_ID_RAWVIDEO,
                       Tag(ColorFourCc(o.color_format)), o.color_width, o.color_height,
                       "K4A_COLOR_MODE", ColorMode(o));
      if (mjpeg) OpenEncoder();
    }
    if (o.depth_width > 0) {
      const std::string mode = DepthMode(o.depth_width, o.depth_height);
      depth = AddVideo("DEPTH", AV_CODEC_ID_RAWVIDEO, Tag("b16g"), o.depth_width, o.depth_height,
                       "K4A_DEPTH_MODE", mode);
      if (o.ir) {
        ir = AddVideo("IR", AV_CODEC_ID_RAWVIDEO, Tag("b16g"), o.depth_width, o.depth_height,
                      "K4A_IR_MODE", "ACTIVE");
      }
    }
    if (!o.calibration_json.empty()) {
      AVStream* a = avformat_new_stream(format, nullptr);
      a->codecpar->codec_type = AVMEDIA_TYPE_ATTACHMENT;
      a->codecpar->extradata = static_cast<uint8_t*>(
          av_mallocz(o.calibration_json.size() + AV_INPUT_BUFFER_PADDING_SIZE));
      std::copy(o.calibration_json.begin(), o.calibration_json.end(), a->codecpar->extradata);
      a->codecpar->extradata_size = static_cast<int>(o.calibration_json.size());
      av_dict_set(&a->metadata, "filename", "calibration.json", 0);
      av_dict_set(&a->metadata, "mimetype", "application/octet-stream", 0);
    }
    av_dict_set(&format->metadata, "K4A_DEPTH_DELAY_NS",
                std::to_string(o.depth_delay_us * 1000).c_str(), 0);
  }

  void Open() {
    av_log_set_level(AV_LOG_FATAL);  // as the reader: libav's warnings are noise, errors are ours
    temporary = target;
    temporary += ".partial";
    if (avformat_alloc_output_context2(&format, nullptr, "matroska", temporary.c_str()) < 0) {
      Fail("no Matroska muxer");
    }
    // Raw tracks as VFW with their FourCC, as k4arecorder writes them.
    av_opt_set_int(format->priv_data, "allow_raw_vfw", 1, 0);
    AddStreams();
    if (avio_open(&format->pb, temporary.c_str(), AVIO_FLAG_WRITE) < 0) Fail("cannot create it");
    if (avformat_init_output(format, nullptr) < 0) Fail("the Matroska muxer refuses the tracks");
    // libav's muxer set-up clears FourCCs it does not know for raw video (b16g, NV12, ...);
    // the track headers are written after it, so the recorder's tags go back in here.
    for (unsigned i = 0; i < format->nb_streams; ++i) {
      AVCodecParameters* p = format->streams[i]->codecpar;
      if (p->codec_id != AV_CODEC_ID_RAWVIDEO) continue;
      const bool color_track = color && format->streams[i] == color;
      p->codec_tag = color_track ? Tag(ColorFourCc(options.color_format)) : Tag("b16g");
      p->bits_per_coded_sample =
          color_track && options.color_format == AzureColorFormat::kBgra ? 32 : 16;
      if (color_track && options.color_format == AzureColorFormat::kNv12) {
        p->bits_per_coded_sample = 12;
      }
    }
    if (avformat_write_header(format, nullptr) < 0) Fail("the Matroska header is refused");
    header_written = true;
    frame = av_frame_alloc();
    packet = av_packet_alloc();
  }

  void WriteBytes(AVStream* stream, const uint8_t* data, int size, int64_t timestamp_us) {
    av_packet_unref(packet);
    if (av_new_packet(packet, size) < 0) Fail("out of memory");
    std::copy(data, data + size, packet->data);
    packet->stream_index = stream->index;
    packet->pts = packet->dts =
        av_rescale_q(timestamp_us, AVRational{1, 1000000}, stream->time_base);
    packet->flags |= AV_PKT_FLAG_KEY;
    if (av_interleaved_write_frame(format, packet) < 0) Fail("a packet is refused");
  }

  // RGB into `target_format` planes in `frame`.
  void Convert(const RgbImage& rgb, AVPixelFormat target_format) {
    av_frame_unref(frame);
    frame->format = target_format;
    frame->width = rgb.width;
    frame->height = rgb.height;
    if (av_frame_get_buffer(frame, 1) < 0) Fail("out of memory");
    scaler = sws_getCachedContext(scaler, rgb.width, rgb.height, AV_PIX_FMT_RGB24, rgb.width,
                                  rgb.height, target_format, SWS_POINT, nullptr, nullptr, nullptr);
    const uint8_t* in[1] = {rgb.pixels.data()};
    const int in_stride[1] = {3 * rgb.width};
    sws_scale(scaler, in, in_stride, 0, rgb.height, frame->data, frame->linesize);
  }

  void WriteColor(const RgbImage& rgb, int64_t timestamp_us) {
    if (rgb.width != options.color_width || rgb.height != options.color_height) {
      Fail(fmt::format("a {}x{} colour image for a {}x{} track", rgb.width, rgb.height,
                       options.color_width, options.color_height));
    }
    const AVPixelFormat pix = RawColorFormat(options.color_format);
    Convert(rgb, pix);
    if (!encoder) {
      const int size = av_image_get_buffer_size(pix, rgb.width, rgb.height, 1);
      std::vector<uint8_t> bytes(static_cast<size_t>(size));
      av_image_copy_to_buffer(bytes.data(), size, frame->data, frame->linesize, pix, rgb.width,
                              rgb.height, 1);
      WriteBytes(color, bytes.data(), size, timestamp_us);
      return;
    }
    frame->pts = timestamp_us;
    if (avcodec_send_frame(encoder, frame) < 0) Fail("the MJPEG encoder refuses a frame");
    AVPacket* encoded = av_packet_alloc();
    while (avcodec_receive_packet(encoder, encoded) == 0) {
      WriteBytes(color, encoded->data, encoded->size, timestamp_us);
      av_packet_unref(encoded);
    }
    av_packet_free(&encoded);
  }

  void WriteB16g(AVStream* stream, const DepthImage& image, int64_t timestamp_us) {
    if (image.width != options.depth_width || image.height != options.depth_height) {
      Fail(fmt::format("a {}x{} depth image for a {}x{} track", image.width, image.height,
                       options.depth_width, options.depth_height));
    }
    std::vector<uint8_t> bytes(image.pixels.size() * 2);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      bytes[2 * i] = static_cast<uint8_t>(image.pixels[i] >> 8);
      bytes[2 * i + 1] = static_cast<uint8_t>(image.pixels[i] & 0xff);
    }
    WriteBytes(stream, bytes.data(), static_cast<int>(bytes.size()), timestamp_us);
  }
};

AzureKinectWriter::AzureKinectWriter(const std::filesystem::path& path,
                                     const AzureWriterOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.Validate();
  impl_->target = path;
  impl_->options = options;
  impl_->Open();
}

AzureKinectWriter::~AzureKinectWriter() = default;

void AzureKinectWriter::Write(const AzureCapture& capture) {
  if (capture.color && impl_->color) impl_->WriteColor(*capture.color, capture.color_timestamp_us);
  if (capture.depth && impl_->depth) {
    impl_->WriteB16g(impl_->depth, *capture.depth, capture.depth_timestamp_us);
  }
  if (capture.ir && impl_->ir) impl_->WriteB16g(impl_->ir, *capture.ir, capture.depth_timestamp_us);
}

void AzureKinectWriter::Close() {
  if (av_write_trailer(impl_->format) < 0) impl_->Fail("the trailer is refused");
  avio_closep(&impl_->format->pb);
  impl_->closed = true;
  std::filesystem::rename(impl_->temporary, impl_->target);
}

}  // namespace simtree
