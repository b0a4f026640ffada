// VideoSink: frames encoded through FFmpeg's libraries (libavcodec, libavformat, libswscale).
// AVI = Motion JPEG, MP4 = H.264. See frame_sinks.h for the output discipline.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>

#include "image/video_module.h"
#include "simbob/tool/frame_sinks.h"

namespace simbob {

namespace {

std::string avError(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

// The output named by its own folder, not by the temporary name it is written under (as
// simbob/tool/files.h cannotCreateReason says it; this module links no simbob library).
std::string missingFolder(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  return "cannot create: folder '" + folder + "' does not exist";
}

// FFmpeg's own log lines would break simbob's one-line errors; every failure is reported from
// the return codes instead.
void quietFfmpeg() {
  static std::once_flag once;
  std::call_once(once, [] { av_log_set_level(AV_LOG_QUIET); });
}

std::string lowerExtension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

struct Choice {
  const AVCodec* codec = nullptr;
  const char* muxer = nullptr;
  AVPixelFormat pix_fmt = AV_PIX_FMT_NONE;
  std::string why;  // when codec is null
};

Choice choose(const std::string& path) {
  quietFfmpeg();
  Choice c;
  const std::string ext = lowerExtension(path);
  if (ext == ".avi") {
    c.muxer = "avi";
    c.codec = avcodec_find_encoder(AV_CODEC_ID_MJPEG);
    c.pix_fmt = AV_PIX_FMT_YUVJ420P;
    if (!c.codec) c.why = "this libavcodec has no Motion JPEG encoder (mjpeg); install Debian's libavcodec59";
  } else if (ext == ".mp4") {
    c.muxer = "mp4";
    c.codec = avcodec_find_encoder_by_name("libx264");
    if (!c.codec) c.codec = avcodec_find_encoder(AV_CODEC_ID_H264);
    c.pix_fmt = AV_PIX_FMT_YUV420P;
    if (!c.codec)
      c.why = "this libavcodec has no H.264 encoder (libx264); install Debian's libavcodec59 and libx264-164";
  } else {
    c.why = "unknown video format '" + ext + "': use .avi (Motion JPEG) or .mp4 (H.264)";
    if (ext.empty()) c.why = "no video format: the file name must end in .avi (Motion JPEG) or .mp4 (H.264)";
  }
  if (c.muxer && !av_guess_format(c.muxer, nullptr, nullptr)) {
    c.codec = nullptr;
    c.why = std::string("this libavformat cannot write ") + c.muxer + " files";
  }
  return c;
}

class VideoSink : public FrameSink {
 public:
  ~VideoSink() override {
    release();
    if (!committed_ && !temp_.empty()) ::unlink(temp_.c_str());
  }

  static std::unique_ptr<FrameSink> open(const std::string& path, double fps, Error* err, const std::string& write_to) {
    auto fail = [&](ErrorKind kind, const std::string& what) {
      if (err) *err = fileError(kind, path, what);
      return nullptr;
    };
    Choice c = choose(path);
    if (!c.codec) return fail(c.muxer ? ErrorKind::CannotCreate : ErrorKind::InvalidInput, c.why);
    if (!(fps > 0 && fps <= 1000))
      return fail(ErrorKind::InvalidInput, "frame rate must be in (0, 1000], got " + std::to_string(fps));
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      return fail(ErrorKind::CannotCreate,
                  S_ISDIR(st.st_mode) ? "cannot create: is a directory" : "cannot create: not a regular file");
    std::unique_ptr<VideoSink> s(new VideoSink());
    s->path_ = path;
    s->choice_ = c;
    s->fps_ = av_d2q(fps, 1000000);
    s->temp_ = write_to.empty() ? path + ".tmp." + std::to_string(static_cast<long>(::getpid())) : write_to;
    s->keep_temp_ = !write_to.empty();
    // Created now so that an output that cannot be written fails before any frame is rendered.
    const int rc = avio_open(&s->io_, s->temp_.c_str(), AVIO_FLAG_WRITE);
    if (rc < 0) {
      s->temp_.clear();  // nothing was created
      return fail(ErrorKind::CannotCreate,
                  rc == AVERROR(ENOENT) ? missingFolder(path) : "cannot create: " + avError(rc));
    }
    return s;
  }

  const Error* add(Image&& frame) override {
    if (failed_) return &error_;
    if (finished_) return fail(ErrorKind::Internal, "frame added after finish()");
    if (frame.width <= 0 || frame.height <= 0)
      return fail(ErrorKind::InvalidInput, "frame " + std::to_string(count_) + " is empty (" +
                                               std::to_string(frame.width) + "x" + std::to_string(frame.height) + ")");
    if (frame.rgb.size() != static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height) * 3)
      return fail(ErrorKind::Internal, "frame " + std::to_string(count_) + " has " + std::to_string(frame.rgb.size()) +
                                           " bytes for " + std::to_string(frame.width) + "x" +
                                           std::to_string(frame.height) + " RGB");
    if (!enc_) {
      if (const Error* e = start(frame.width, frame.height)) return e;
    } else if (frame.width != enc_->width || frame.height != enc_->height) {
      return fail(ErrorKind::InvalidInput, "frame " + std::to_string(count_) + " is " + std::to_string(frame.width) +
                                               "x" + std::to_string(frame.height) + ", the video is " +
                                               std::to_string(enc_->width) + "x" + std::to_string(enc_->height));
    }
    int rc = av_frame_make_writable(yuv_);
    if (rc < 0) return fail(ErrorKind::Internal, "cannot allocate a frame: " + avError(rc));
    const uint8_t* src[1] = {frame.rgb.data()};
    const int stride[1] = {frame.width * 3};
    sws_scale(sws_, src, stride, 0, frame.height, yuv_->data, yuv_->linesize);
    yuv_->pts = count_;
    if (const Error* e = encode(yuv_)) return e;
    ++count_;
    return nullptr;
  }

  const Error* finish() override {
    if (failed_) return &error_;
    if (finished_) return nullptr;
    if (!enc_) return fail(ErrorKind::InvalidInput, "no frames to write");
    if (const Error* e = encode(nullptr)) return e;
    int rc = av_write_trailer(fmt_);
    if (rc < 0) return fail(ErrorKind::IoError, "write failed: " + avError(rc));
    rc = avio_closep(&fmt_->pb);
    io_ = nullptr;
    if (rc < 0) return fail(ErrorKind::IoError, "write failed: " + avError(rc));
    release();
    // Given a file to write to, the caller commits it with the run's other outputs.
    if (!keep_temp_ && std::rename(temp_.c_str(), path_.c_str()) != 0)
      return fail(ErrorKind::CannotCreate, std::string("cannot create: ") + std::strerror(errno));
    committed_ = true;
    finished_ = true;
    temp_.clear();
    return nullptr;
  }

 private:
  VideoSink() = default;

  const Error* fail(ErrorKind kind, std::string message) {
    if (!failed_) error_ = fileError(kind, path_, std::move(message));
    failed_ = true;
    release();
    if (!temp_.empty()) ::unlink(temp_.c_str());
    temp_.clear();
    return &error_;
  }

  void release() {
    if (enc_) avcodec_free_context(&enc_);
    if (yuv_) av_frame_free(&yuv_);
    if (pkt_) av_packet_free(&pkt_);
    if (sws_) {
      sws_freeContext(sws_);
      sws_ = nullptr;
    }
    if (fmt_) {
      if (fmt_->pb) avio_closep(&fmt_->pb);
      io_ = nullptr;
      avformat_free_context(fmt_);
      fmt_ = nullptr;
    }
    if (io_) avio_closep(&io_);
  }

  const Error* start(int w, int h) {
    const bool h264 = choice_.codec->id == AV_CODEC_ID_H264;
    if (h264 && (w % 2 != 0 || h % 2 != 0))
      return fail(ErrorKind::InvalidInput, "H.264 needs an even width and height, the frames are " + std::to_string(w) +
                                               "x" + std::to_string(h) + " (use .avi, or an even --size)");
    int rc = avformat_alloc_output_context2(&fmt_, nullptr, choice_.muxer, temp_.c_str());
    if (rc < 0 || !fmt_)
      return fail(ErrorKind::Internal, std::string("cannot set up ") + choice_.muxer + ": " + avError(rc));
    fmt_->pb = io_;
    // No "Lavf59..." encoder tags and no timestamps of the moment: same frames, same bytes.
    fmt_->flags |= AVFMT_FLAG_BITEXACT;
    AVStream* st = avformat_new_stream(fmt_, nullptr);
    enc_ = avcodec_alloc_context3(choice_.codec);
    yuv_ = av_frame_alloc();
    pkt_ = av_packet_alloc();
    if (!st || !enc_ || !yuv_ || !pkt_) return fail(ErrorKind::Internal, "out of memory setting up the encoder");
    enc_->width = w;
    enc_->height = h;
    enc_->time_base = av_inv_q(fps_);
    enc_->framerate = fps_;
    enc_->pix_fmt = choice_.pix_fmt;
    enc_->flags |= AV_CODEC_FLAG_BITEXACT;
    enc_->thread_count = 1;  // x264's output depends on its thread count
    AVDictionary* opts = nullptr;
    if (choice_.codec->id == AV_CODEC_ID_MJPEG) {
      // Fixed quantiser 3 (of 2..31): sharp frames, about 1/10 of the raw size.
      enc_->flags |= AV_CODEC_FLAG_QSCALE;
      enc_->global_quality = FF_QP2LAMBDA * 3;
      enc_->color_range = AVCOL_RANGE_JPEG;
    } else {
      enc_->gop_size = std::max(1, static_cast<int>(std::lround(av_q2d(fps_) * 2)));  // a key frame every 2 s
      enc_->color_range = AVCOL_RANGE_MPEG;
      if (std::strcmp(choice_.codec->name, "libx264") == 0) {
        av_dict_set(&opts, "preset", "veryfast", 0);
        av_dict_set(&opts, "crf", "20", 0);
      }
    }
    if (fmt_->oformat->flags & AVFMT_GLOBALHEADER) enc_->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    rc = avcodec_open2(enc_, choice_.codec, &opts);
    av_dict_free(&opts);
    if (rc < 0)
      return fail(ErrorKind::CannotCreate,
                  std::string("cannot open the ") + choice_.codec->name + " encoder: " + avError(rc));
    rc = avcodec_parameters_from_context(st->codecpar, enc_);
    if (rc < 0) return fail(ErrorKind::Internal, "cannot set stream parameters: " + avError(rc));
    st->time_base = enc_->time_base;
    st->avg_frame_rate = fps_;
    st->r_frame_rate = fps_;
    yuv_->format = enc_->pix_fmt;
    yuv_->width = w;
    yuv_->height = h;
    rc = av_frame_get_buffer(yuv_, 0);
    if (rc < 0) return fail(ErrorKind::Internal, "cannot allocate a frame: " + avError(rc));
    // Bit-exact C code paths: the same RGB gives the same YUV on every CPU.
    sws_ = sws_getContext(w, h, AV_PIX_FMT_RGB24, w, h, enc_->pix_fmt, SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT,
                          nullptr, nullptr, nullptr);
    if (!sws_) return fail(ErrorKind::Internal, "cannot set up the RGB to YUV conversion");
    rc = avformat_write_header(fmt_, nullptr);
    if (rc < 0) return fail(ErrorKind::IoError, "write failed: " + avError(rc));
    return nullptr;
  }

  // Sends one frame (null: end of stream) and writes every packet the encoder has ready.
  const Error* encode(AVFrame* frame) {
    int rc = avcodec_send_frame(enc_, frame);
    if (rc < 0) return fail(ErrorKind::IoError, std::string(choice_.codec->name) + " encoder failed: " + avError(rc));
    for (;;) {
      rc = avcodec_receive_packet(enc_, pkt_);
      if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return nullptr;
      if (rc < 0) return fail(ErrorKind::IoError, std::string(choice_.codec->name) + " encoder failed: " + avError(rc));
      AVStream* st = fmt_->streams[0];
      av_packet_rescale_ts(pkt_, enc_->time_base, st->time_base);
      pkt_->stream_index = st->index;
      rc = av_interleaved_write_frame(fmt_, pkt_);  // takes the packet's data
      if (rc < 0) return fail(ErrorKind::IoError, "write failed: " + avError(rc));
    }
  }

  std::string path_, temp_;
  Choice choice_;
  AVRational fps_{30, 1};
  AVIOContext* io_ = nullptr;
  AVFormatContext* fmt_ = nullptr;
  AVCodecContext* enc_ = nullptr;
  AVFrame* yuv_ = nullptr;
  AVPacket* pkt_ = nullptr;
  SwsContext* sws_ = nullptr;
  int64_t count_ = 0;
  bool failed_ = false;
  bool finished_ = false;
  bool committed_ = false;
  bool keep_temp_ = false;  ///< temp_ is the caller's: finish() leaves it for the caller to commit
  Error error_;
};

}  // namespace

std::string ffmpegEncoderFor(const std::string& path, std::string* why) {
  Choice c = choose(path);
  if (!c.codec) {
    if (why) *why = c.why;
    return "";
  }
  return c.codec->name;
}

std::unique_ptr<FrameSink> ffmpegVideoSink(const std::string& path, double fps, Error* err,
                                           const std::string& write_to) {
  return VideoSink::open(path, fps, err, write_to);
}

}  // namespace simbob
