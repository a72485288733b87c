// libavcodec (MJPEG) and libswscale (every colour layout to RGB24) behind the frame decoders.

#include "simtree/io/detail/azure_frame_decoder.h"

#include <string>

#include <fmt/format.h>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/imgutils.h>
#include <libswscale/swscale.h>
}

#include "simtree/core/error.h"

namespace simtree::azure_detail {
namespace {

std::string Where(const AzureTrack& track, int frame) {
  return fmt::format("{} frame {}", track.name, frame);
}

// The raw layouts the recorder writes as Matroska VFW tracks, by FourCC.
AVPixelFormat RawFormat(const std::string& fourcc) {
  if (fourcc == "NV12") return AV_PIX_FMT_NV12;
  if (fourcc == "YUY2") return AV_PIX_FMT_YUYV422;
  if (fourcc == "BGRA") return AV_PIX_FMT_BGRA;
  return AV_PIX_FMT_NONE;
}

}  // namespace

DepthImage DecodeB16g(const uint8_t* data, int size, const AzureTrack& track,
                      const std::string& source, int frame) {
  const int64_t expected = static_cast<int64_t>(track.width) * track.height * 2;
  if (size != expected) {
    throw InputError(source, Where(track, frame),
                     fmt::format("expected {} bytes ({}x{} 16-bit), got {} (truncated or corrupt "
                                 "file?)",
                                 expected, track.width, track.height, size));
  }
  DepthImage image(track.width, track.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] = static_cast<uint16_t>((data[2 * i] << 8) | data[2 * i + 1]);
  }
  return image;
}

struct ColorDecoder::Impl {
  std::string source;
  AzureTrack track;
  AVPixelFormat raw_format = AV_PIX_FMT_NONE;  // NONE: MJPEG through the decoder
  AVCodecContext* codec = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scaler = nullptr;
  ~Impl() {
    sws_freeContext(scaler);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
  }

  // RGB24 from planes in `format`; the scaler is made once per format.
  RgbImage Convert(const uint8_t* const planes[4], const int strides[4], AVPixelFormat format) {
    scaler =
        sws_getCachedContext(scaler, track.width, track.height, format, track.width, track.height,
                             AV_PIX_FMT_RGB24, SWS_POINT, nullptr, nullptr, nullptr);
    if (!scaler) {
      throw InputError(
          source, track.name,
          fmt::format("cannot convert colour format {} to RGB", av_get_pix_fmt_name(format)));
    }
    RgbImage image(track.width, track.height);
    uint8_t* out[1] = {image.pixels.data()};
    const int out_stride[1] = {3 * track.width};
    sws_scale(scaler, planes, strides, 0, track.height, out, out_stride);
    return image;
  }

  RgbImage DecodeRaw(const uint8_t* data, int size, int index) {
    const int expected = av_image_get_buffer_size(raw_format, track.width, track.height, 1);
    if (size != expected) {
      throw InputError(source, Where(track, index),
                       fmt::format("expected {} bytes of {} {}x{}, got {} (truncated or corrupt "
                                   "file?)",
                                   expected, track.fourcc, track.width, track.height, size));
    }
    uint8_t* planes[4] = {};
    int strides[4] = {};
    av_image_fill_arrays(planes, strides, data, raw_format, track.width, track.height, 1);
    return Convert(planes, strides, raw_format);
  }

  RgbImage DecodeCompressed(const uint8_t* data, int size, int index) {
    av_packet_unref(packet);
    packet->data = const_cast<uint8_t*>(data);
    packet->size = size;
    int status = avcodec_send_packet(codec, packet);
    if (status >= 0) status = avcodec_receive_frame(codec, frame);
    packet->data = nullptr;
    packet->size = 0;
    if (status < 0 || frame->width != track.width || frame->height != track.height) {
      throw InputError(source, Where(track, index),
                       fmt::format("expected a {}x{} {} image, it does not decode (truncated or "
                                   "corrupt file?)",
                                   track.width, track.height, track.fourcc));
    }
    return Convert(frame->data, frame->linesize, static_cast<AVPixelFormat>(frame->format));
  }
};

ColorDecoder::ColorDecoder(const MkvStream& stream, std::string source)
    : impl_(std::make_unique<Impl>()) {
  impl_->source = std::move(source);
  impl_->track = stream.track;
  impl_->frame = av_frame_alloc();
  impl_->packet = av_packet_alloc();
  const AVCodecParameters* p = stream.parameters;
  if (p->codec_id == AV_CODEC_ID_MJPEG) {
    const AVCodec* decoder = avcodec_find_decoder(AV_CODEC_ID_MJPEG);
    impl_->codec = avcodec_alloc_context3(decoder);
    avcodec_parameters_to_context(impl_->codec, p);
    impl_->codec->thread_count = 1;
    impl_->codec->err_recognition = AV_EF_EXPLODE;  // a damaged JPEG is an error, not concealed
    if (!decoder || avcodec_open2(impl_->codec, decoder, nullptr) < 0) {
      throw InputError(impl_->source, stream.track.name, "libav has no usable MJPEG decoder");
    }
    return;
  }
  impl_->raw_format =
      p->codec_id == AV_CODEC_ID_RAWVIDEO ? RawFormat(stream.track.fourcc) : AV_PIX_FMT_NONE;
  if (impl_->raw_format == AV_PIX_FMT_NONE) {
    throw InputError(impl_->source, stream.track.name,
                     fmt::format("expected colour in MJPEG, NV12, YUY2 or BGRA, got codec {} "
                                 "FourCC '{}'",
                                 stream.track.codec, stream.track.fourcc));
  }
}

ColorDecoder::~ColorDecoder() = default;

RgbImage ColorDecoder::Decode(const uint8_t* data, int size, int frame) {
  if (impl_->raw_format != AV_PIX_FMT_NONE) return impl_->DecodeRaw(data, size, frame);
  return impl_->DecodeCompressed(data, size, frame);
}

}  // namespace simtree::azure_detail
