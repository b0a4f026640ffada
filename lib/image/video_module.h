// The FFmpeg side of lib/image, built as a module of its own (libsimbob_video.so) and opened on
// demand by video_loader.cpp: a run that writes no video never loads FFmpeg's libraries, whose
// start-up code (libhwy, through libjxl) does not run under valgrind on every CPU. The module's
// functions are those of frame_sinks.h and video_probe.h under other names; the executable that
// opens it provides simbob's own symbols (it is linked with ENABLE_EXPORTS).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "simbob/tool/frame_sinks.h"
#include "simbob/tool/video_probe.h"

namespace simbob {

std::string ffmpegEncoderFor(const std::string& path, std::string* why);
std::unique_ptr<FrameSink> ffmpegVideoSink(const std::string& path, double fps, Error* err,
                                           const std::string& write_to);
Error ffmpegProbeVideo(const std::string& path, VideoInfo* info, int64_t frame_index, Image* frame);

/// What simbob_video_module() returns; `abi` is kVideoModuleAbi of the module's build.
struct VideoModule {
  int abi;
  std::string (*encoder_for)(const std::string& path, std::string* why);
  std::unique_ptr<FrameSink> (*make_sink)(const std::string& path, double fps, Error* err, const std::string& write_to);
  Error (*probe)(const std::string& path, VideoInfo* info, int64_t frame_index, Image* frame);
};
constexpr int kVideoModuleAbi = 2;  // 2: make_sink's write_to

}  // namespace simbob

extern "C" const simbob::VideoModule* simbob_video_module();
