// makeVideoSink, videoEncoderFor and probeVideo open libsimbob_video.so (FFmpeg) the first time
// they are called: beside the executable, one folder up (tests and benchmarks in the build tree),
// or in ../lib/simbob (an installed simbob). SIMBOB_VIDEO_MODULE names the file explicitly.

#include "image/video_module.h"
#include "simbob/tool/platform.h"

namespace simbob {

namespace {

/// The module's table, or nullptr with `why` set.
const VideoModule* videoModule(std::string* why) {
  return simbobModule<VideoModule>("libsimbob_video.so", "SIMBOB_VIDEO_MODULE", "simbob_video_module", kVideoModuleAbi,
                                   "video output needs libsimbob_video.so (FFmpeg)", nullptr, why);
}

}  // namespace

std::string videoEncoderFor(const std::string& path, std::string* why) {
  const VideoModule* m = videoModule(why);
  return m ? m->encoder_for(path, why) : std::string();
}

std::unique_ptr<FrameSink> makeVideoSink(const std::string& path, double fps, Error* err, const std::string& write_to) {
  std::string why;
  const VideoModule* m = videoModule(&why);
  if (!m) {
    if (err) *err = Error{ErrorKind::MissingInput, {path}, why};
    return nullptr;
  }
  return m->make_sink(path, fps, err, write_to);
}

Error probeVideo(const std::string& path, VideoInfo* info, int64_t frame_index, Image* frame) {
  std::string why;
  const VideoModule* m = videoModule(&why);
  if (!m) return Error{ErrorKind::MissingInput, {path}, why};
  return m->probe(path, info, frame_index, frame);
}

}  // namespace simbob
