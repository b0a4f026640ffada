// The entry point of libsimbob_video.so (see video_module.h).
#include "image/video_module.h"

extern "C" __attribute__((visibility("default"))) const simbob::VideoModule* simbob_video_module() {
  static const simbob::VideoModule m{simbob::kVideoModuleAbi, &simbob::ffmpegEncoderFor, &simbob::ffmpegVideoSink,
                                     &simbob::ffmpegProbeVideo};
  return &m;
}
