// Opening a written video again with FFmpeg's libraries (issue #12: videos are checked by
// frame count, size and frame rate). For tests and benchmarks; no GL, no ODE.
#pragma once

#include <cstdint>
#include <string>

#include "simbob/error.h"
#include "simbob/image.h"

namespace simbob {

struct VideoInfo {
  std::string container;  ///< libavformat's name, e.g. "avi", "mov,mp4,m4a,3gp,3g2,mj2"
  std::string codec;      ///< e.g. "mjpeg", "h264"
  int width = 0;
  int height = 0;
  double fps = 0;      ///< the stream's average frame rate
  int64_t frames = 0;  ///< counted by decoding every frame, not read from the header
};

/// Opens the video at path, decodes every frame of its first video stream and fills *info.
/// When `frame_index` >= 0 and that frame exists, it is also returned in *frame as RGB8.
/// Returns an Error whose message is empty on success (MissingInput / InvalidInput otherwise).
Error probeVideo(const std::string& path, VideoInfo* info, int64_t frame_index = -1, Image* frame = nullptr);

}  // namespace simbob
