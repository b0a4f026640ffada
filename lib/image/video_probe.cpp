extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include "image/video_module.h"
#include "simbob/tool/video_probe.h"

namespace simbob {

namespace {

std::string avError(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

struct Decoder {
  AVFormatContext* fmt = nullptr;
  AVCodecContext* dec = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* pkt = nullptr;
  ~Decoder() {
    av_packet_free(&pkt);
    av_frame_free(&frame);
    avcodec_free_context(&dec);
    avformat_close_input(&fmt);
  }
};

Image toRgb(const AVFrame* f) {
  Image img(f->width, f->height);
  SwsContext* sws =
      sws_getContext(f->width, f->height, static_cast<AVPixelFormat>(f->format), f->width, f->height, AV_PIX_FMT_RGB24,
                     SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
  if (!sws) return Image();
  uint8_t* dst[1] = {img.rgb.data()};
  const int stride[1] = {img.width * 3};
  sws_scale(sws, f->data, f->linesize, 0, f->height, dst, stride);
  sws_freeContext(sws);
  return img;
}

}  // namespace

Error ffmpegProbeVideo(const std::string& path, VideoInfo* info, int64_t frame_index, Image* frame) {
  av_log_set_level(AV_LOG_QUIET);
  *info = VideoInfo();
  if (frame) *frame = Image();
  Error err;
  err.loc.file = path;
  auto fail = [&](ErrorKind kind, std::string what) {
    err.kind = kind;
    err.message = std::move(what);
    return err;
  };
  Decoder d;
  int rc = avformat_open_input(&d.fmt, path.c_str(), nullptr, nullptr);
  if (rc < 0) return fail(rc == AVERROR(ENOENT) ? ErrorKind::MissingInput : ErrorKind::InvalidInput, avError(rc));
  rc = avformat_find_stream_info(d.fmt, nullptr);
  if (rc < 0) return fail(ErrorKind::InvalidInput, "no stream information: " + avError(rc));
  const int si = av_find_best_stream(d.fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (si < 0) return fail(ErrorKind::InvalidInput, "no video stream");
  AVStream* st = d.fmt->streams[si];
  const AVCodec* codec = avcodec_find_decoder(st->codecpar->codec_id);
  if (!codec)
    return fail(ErrorKind::InvalidInput, "no decoder for " + std::string(avcodec_get_name(st->codecpar->codec_id)));
  d.dec = avcodec_alloc_context3(codec);
  d.frame = av_frame_alloc();
  d.pkt = av_packet_alloc();
  if (!d.dec || !d.frame || !d.pkt) return fail(ErrorKind::Internal, "out of memory");
  avcodec_parameters_to_context(d.dec, st->codecpar);
  d.dec->thread_count = 1;
  rc = avcodec_open2(d.dec, codec, nullptr);
  if (rc < 0) return fail(ErrorKind::InvalidInput, "cannot open the decoder: " + avError(rc));
  info->container = d.fmt->iformat->name;
  info->codec = codec->name;
  info->width = st->codecpar->width;
  info->height = st->codecpar->height;
  info->fps = st->avg_frame_rate.den ? av_q2d(st->avg_frame_rate) : 0.0;

  auto drain = [&]() -> int {
    for (;;) {
      const int r = avcodec_receive_frame(d.dec, d.frame);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return 0;
      if (r < 0) return r;
      if (frame && info->frames == frame_index) *frame = toRgb(d.frame);
      ++info->frames;
      av_frame_unref(d.frame);
    }
  };
  while ((rc = av_read_frame(d.fmt, d.pkt)) >= 0) {
    if (d.pkt->stream_index == si) {
      rc = avcodec_send_packet(d.dec, d.pkt);
      av_packet_unref(d.pkt);
      if (rc < 0)
        return fail(ErrorKind::InvalidInput,
                    "cannot decode frame " + std::to_string(info->frames) + ": " + avError(rc));
      rc = drain();
      if (rc < 0)
        return fail(ErrorKind::InvalidInput,
                    "cannot decode frame " + std::to_string(info->frames) + ": " + avError(rc));
    } else {
      av_packet_unref(d.pkt);
    }
  }
  if (rc != AVERROR_EOF) return fail(ErrorKind::InvalidInput, "cannot read: " + avError(rc));
  avcodec_send_packet(d.dec, nullptr);
  rc = drain();
  if (rc < 0)
    return fail(ErrorKind::InvalidInput, "cannot decode frame " + std::to_string(info->frames) + ": " + avError(rc));
  return Error();
}

}  // namespace simbob
