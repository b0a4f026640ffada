// simbob_write_test_video PATH FRAMES FPS: writes FRAMES synthetic 160x120 frames (moving
// squares) to the video PATH through makeVideoSink, for tests/image/ffprobe.sh.
#include <cstdio>
#include <cstdlib>

#include "image_test_util.h"
#include "simbob/tool/frame_sinks.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: simbob_write_test_video PATH FRAMES FPS\n");
    return 64;
  }
  simbob::Error err;
  std::unique_ptr<simbob::FrameSink> sink = simbob::makeVideoSink(argv[1], std::atof(argv[3]), &err);
  if (!sink) {
    std::fprintf(stderr, "%s\n", err.str().c_str());
    return 73;
  }
  const int frames = std::atoi(argv[2]);
  for (int i = 0; i < frames; ++i)
    if (const simbob::Error* e = sink->add(simbob_test::movingSquares(160, 120, i))) {
      std::fprintf(stderr, "%s\n", e->str().c_str());
      return 74;
    }
  if (const simbob::Error* e = sink->finish()) {
    std::fprintf(stderr, "%s\n", e->str().c_str());
    return 74;
  }
  return 0;
}
