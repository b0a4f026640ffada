// lib/image: PNG sequences, videos through FFmpeg, and the asynchronous sink in front of them.
#include "simbob/tool/frame_sinks.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "image_test_util.h"
#include "simbob/tool/image_compare.h"
#include "simbob/tool/png.h"
#include "simbob/tool/video_probe.h"

namespace fs = std::filesystem;
using simbob::Error;
using simbob::ErrorKind;
using simbob::FrameSink;
using simbob::Image;
using simbob_test::ImageTempDir;
using simbob_test::movingSquares;
using simbob_test::slurp;

namespace {

size_t entries(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

std::string frameFile(const fs::path& dir, int n) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06d.png", n);
  return (dir / buf).string();
}

// Writes n moving-squares frames of w x h to sink and finishes it.
void record(FrameSink& sink, int n, int w = 160, int h = 120) {
  for (int i = 0; i < n; ++i) REQUIRE(sink.add(movingSquares(w, h, i)) == nullptr);
  const Error* e = sink.finish();
  INFO((e ? e->str() : ""));
  REQUIRE(e == nullptr);
}

std::string writeVideo(const std::string& path, int n, double fps = 10) {
  Error err;
  std::unique_ptr<FrameSink> sink = simbob::makeVideoSink(path, fps, &err);
  INFO(err.str());
  REQUIRE(sink);
  record(*sink, n);
  return slurp(path);
}

// A sink that keeps what it gets and can be told to fail at frame `fail_at`.
struct MemorySink : FrameSink {
  std::vector<Image>* frames;
  int fail_at;
  bool* finished;
  Error error;
  MemorySink(std::vector<Image>* f, int fail, bool* fin) : frames(f), fail_at(fail), finished(fin) {}
  const Error* add(Image&& frame) override {
    if (static_cast<int>(frames->size()) == fail_at) {
      error.kind = ErrorKind::IoError;
      error.loc.file = "memory";
      error.message = "frame " + std::to_string(fail_at) + " refused";
      return &error;
    }
    frames->push_back(std::move(frame));
    return nullptr;
  }
  const Error* finish() override {
    *finished = true;
    return nullptr;
  }
};

}  // namespace

TEST_CASE("PNG sequence: numbered frames, and a new recording replaces an old one whole", "[image][sinks]") {
  ImageTempDir tmp;
  const fs::path dir = tmp.path / "out" / "frames";  // neither exists yet
  Error err;
  std::unique_ptr<FrameSink> sink = simbob::makePngSequenceSink(dir.string(), &err);
  REQUIRE(sink);
  record(*sink, 5);
  CHECK(entries(dir) == 5);  // no staging directory left
  for (int i = 0; i < 5; ++i) {
    Image back;
    REQUIRE(simbob::readPng(frameFile(dir, i), back).message.empty());
    CHECK(back.rgb == movingSquares(160, 120, i).rgb);
  }
  std::ofstream(dir / "notes.txt") << "mine";

  // A failed recording leaves the earlier one as it was.
  sink = simbob::makePngSequenceSink(dir.string(), &err);
  REQUIRE(sink);
  REQUIRE(sink->add(movingSquares(160, 120, 9)) == nullptr);
  Image bad(160, 120);
  bad.rgb.resize(3);
  const Error* e = sink->add(std::move(bad));
  REQUIRE(e);
  CHECK(e->kind == ErrorKind::InvalidInput);
  CHECK(e->str() == frameFile(dir, 1) + ": cannot write PNG: image data has 3 bytes, 160x120 RGB needs 57600");
  CHECK(sink->add(movingSquares(160, 120, 2)) == e);  // the recording stays stopped
  CHECK(sink->finish() == e);
  sink.reset();
  CHECK(entries(dir) == 6);
  Image back;
  REQUIRE(simbob::readPng(frameFile(dir, 0), back).message.empty());
  CHECK(back.rgb == movingSquares(160, 120, 0).rgb);

  // Abandoned without finish(): the same.
  sink = simbob::makePngSequenceSink(dir.string(), &err);
  REQUIRE(sink->add(movingSquares(160, 120, 9)) == nullptr);
  sink.reset();
  CHECK(entries(dir) == 6);

  // A shorter recording: frames 0..2 replaced, 3 and 4 of the old one removed, other files kept.
  sink = simbob::makePngSequenceSink(dir.string(), &err);
  for (int i = 0; i < 3; ++i) REQUIRE(sink->add(movingSquares(160, 120, 10 + i)) == nullptr);
  REQUIRE(sink->finish() == nullptr);
  CHECK(entries(dir) == 4);
  CHECK(fs::exists(dir / "notes.txt"));
  CHECK_FALSE(fs::exists(frameFile(dir, 3)));
  REQUIRE(simbob::readPng(frameFile(dir, 2), back).message.empty());
  CHECK(back.rgb == movingSquares(160, 120, 12).rgb);
}

TEST_CASE("PNG sequence: directories that cannot hold frames", "[image][sinks]") {
  ImageTempDir tmp;
  const std::string file = (tmp.path / "file").string();
  std::ofstream(file) << "x";
  Error err;
  CHECK_FALSE(simbob::makePngSequenceSink(file, &err));
  CHECK(err.kind == ErrorKind::CannotCreate);
  CHECK(err.str() == file + ": cannot create frames: not a directory");
  CHECK_FALSE(simbob::makePngSequenceSink(file + "/sub", &err));
  CHECK(err.kind == ErrorKind::CannotCreate);
  CHECK(err.str().rfind(file + "/sub: cannot create directory: ", 0) == 0);
  CHECK_FALSE(simbob::makePngSequenceSink("", &err));
  CHECK(err.message == "empty output directory name");

  // A recording abandoned in a directory it created leaves no directory behind.
  const fs::path fresh = tmp.path / "a" / "b";
  std::unique_ptr<FrameSink> sink = simbob::makePngSequenceSink(fresh.string(), &err);
  REQUIRE(sink);
  REQUIRE(sink->add(movingSquares(16, 16, 0)) == nullptr);
  sink.reset();
  CHECK_FALSE(fs::exists(tmp.path / "a"));
}

TEST_CASE("video: AVI (Motion JPEG) and MP4 (H.264) hold every frame at the frame rate", "[image][video]") {
  ImageTempDir tmp;
  struct Case {
    const char* name;
    const char* codec;
    int tolerance;  // per channel, after lossy compression and 4:2:0 chroma
  };
  for (const Case& c : {Case{"v.avi", "mjpeg", 64}, Case{"v.mp4", "h264", 64}}) {
    INFO(c.name);
    const std::string path = (tmp.path / c.name).string();
    const std::string bytes = writeVideo(path, 12, 10);
    simbob::VideoInfo info;
    Image frame5;
    const Error e = simbob::probeVideo(path, &info, 5, &frame5);
    INFO(e.str());
    REQUIRE(e.message.empty());
    CHECK(info.codec == c.codec);
    CHECK(info.frames == 12);
    CHECK(info.width == 160);
    CHECK(info.height == 120);
    CHECK(info.fps == Approx(10.0));
    // Frame 5 decoded is frame 5 as given, within what JPEG / H.264 change: most pixels within
    // 16, and the worst only at the squares' sharp edges (chroma is kept at half resolution).
    REQUIRE(frame5.width == 160);
    const simbob::ImageComparison close = simbob::compareImages(frame5, movingSquares(160, 120, 5), {16, 0.05});
    INFO(close.summary());
    CHECK(close.matches);
    // ... and it is not frame 4 or 6: the squares have moved.
    CHECK_FALSE(simbob::compareImages(frame5, movingSquares(160, 120, 4), {c.tolerance, 0.005}).matches);
    CHECK_FALSE(simbob::compareImages(frame5, movingSquares(160, 120, 6), {c.tolerance, 0.005}).matches);
    // Deterministic: the same frames give the same bytes. Nothing but the video is left.
    const std::string again = (tmp.path / (std::string("again_") + c.name)).string();
    CHECK(writeVideo(again, 12, 10) == bytes);
  }
  CHECK(entries(tmp.path) == 4);

  simbob::VideoInfo info;
  REQUIRE(simbob::probeVideo((tmp.path / "v.avi").string(), &info).message.empty());
  CHECK(info.frames == 12);
  const std::string slow = (tmp.path / "slow.avi").string();
  writeVideo(slow, 3, 2.5);
  REQUIRE(simbob::probeVideo(slow, &info).message.empty());
  CHECK(info.fps == Approx(2.5));
  CHECK(info.frames == 3);
}

TEST_CASE("video: bad names, bad frames and unwritable places give clear errors", "[image][video]") {
  ImageTempDir tmp;
  Error err;
  const std::string mkv = (tmp.path / "v.mkv").string();
  CHECK_FALSE(simbob::makeVideoSink(mkv, 30, &err));
  CHECK(err.kind == ErrorKind::InvalidInput);
  CHECK(err.str() == mkv + ": unknown video format '.mkv': use .avi (Motion JPEG) or .mp4 (H.264)");
  CHECK_FALSE(simbob::makeVideoSink((tmp.path / "video").string(), 30, &err));
  CHECK(err.message == "no video format: the file name must end in .avi (Motion JPEG) or .mp4 (H.264)");
  CHECK(simbob::videoEncoderFor("X.AVI", nullptr) == "mjpeg");
  CHECK_FALSE(simbob::makeVideoSink((tmp.path / "v.avi").string(), 0, &err));
  CHECK(err.message == "frame rate must be in (0, 1000], got 0.000000");

  const std::string nowhere = (tmp.path / "no" / "v.avi").string();
  CHECK_FALSE(simbob::makeVideoSink(nowhere, 30, &err));
  CHECK(err.kind == ErrorKind::CannotCreate);
  CHECK(err.str() == nowhere + ": cannot create: folder '" + (tmp.path / "no").string() + "' does not exist");
  fs::create_directory(tmp.path / "d.avi");
  CHECK_FALSE(simbob::makeVideoSink((tmp.path / "d.avi").string(), 30, &err));
  CHECK(err.message == "cannot create: is a directory");

  // An existing video is not replaced by a recording that fails.
  const std::string keep = (tmp.path / "keep.avi").string();
  std::ofstream(keep) << "old video";
  std::unique_ptr<FrameSink> sink = simbob::makeVideoSink(keep, 30, &err);
  REQUIRE(sink);
  REQUIRE(sink->add(movingSquares(160, 120, 0)) == nullptr);
  const Error* e = sink->add(movingSquares(320, 240, 1));
  REQUIRE(e);
  CHECK(e->kind == ErrorKind::InvalidInput);
  CHECK(e->str() == keep + ": frame 1 is 320x240, the video is 160x120");
  CHECK(sink->finish() == e);
  sink.reset();
  CHECK(slurp(keep) == "old video");

  sink = simbob::makeVideoSink(keep, 30, &err);
  e = sink->add(Image());
  REQUIRE(e);
  CHECK(e->str() == keep + ": frame 0 is empty (0x0)");
  sink = simbob::makeVideoSink(keep, 30, &err);
  e = sink->finish();
  REQUIRE(e);
  CHECK(e->str() == keep + ": no frames to write");
  sink = simbob::makeVideoSink((tmp.path / "odd.mp4").string(), 30, &err);
  e = sink->add(movingSquares(161, 120, 0));
  REQUIRE(e);
  CHECK(e->message == "H.264 needs an even width and height, the frames are 161x120 (use .avi, or an even --size)");
  sink = simbob::makeVideoSink(keep, 30, &err);
  REQUIRE(sink->add(movingSquares(16, 16, 0)) == nullptr);
  sink.reset();  // abandoned
  CHECK(slurp(keep) == "old video");
  CHECK(entries(tmp.path) == 2);  // keep.avi and the directory d.avi: no temporary files
}

TEST_CASE("async sink: every frame reaches every sink in order; errors surface later", "[image][async]") {
  ImageTempDir tmp;
  std::vector<Image> got;
  bool finished = false;
  std::vector<std::unique_ptr<FrameSink>> sinks;
  Error err;
  sinks.push_back(simbob::makeVideoSink((tmp.path / "async.avi").string(), 10, &err));
  sinks.push_back(std::make_unique<MemorySink>(&got, -1, &finished));
  std::unique_ptr<FrameSink> async = simbob::makeAsyncSink(std::move(sinks), 2);
  record(*async, 12);
  CHECK(finished);
  REQUIRE(got.size() == 12);
  for (int i = 0; i < 12; ++i) CHECK(got[static_cast<size_t>(i)].rgb == movingSquares(160, 120, i).rgb);
  // The same bytes as the video written directly.
  CHECK(slurp((tmp.path / "async.avi").string()) == writeVideo((tmp.path / "direct.avi").string(), 12, 10));
  CHECK(async->finish() == nullptr);  // finishing twice is harmless

  // A sink that fails at frame 3: the error comes back from a later add() or from finish(), and
  // the video beside it is not committed.
  got.clear();
  finished = false;
  sinks.clear();
  sinks.push_back(simbob::makeVideoSink((tmp.path / "failed.avi").string(), 10, &err));
  sinks.push_back(std::make_unique<MemorySink>(&got, 3, &finished));
  async = simbob::makeAsyncSink(std::move(sinks), 1);
  const Error* e = nullptr;
  for (int i = 0; i < 50 && !e; ++i) e = async->add(movingSquares(160, 120, i));
  if (!e) e = async->finish();
  REQUIRE(e);
  CHECK(e->str() == "memory: frame 3 refused");
  CHECK(async->finish() == e);
  CHECK_FALSE(finished);
  async.reset();
  CHECK(got.size() == 3);
  CHECK_FALSE(fs::exists(tmp.path / "failed.avi"));

  // Destroyed without finish(): the worker stops and nothing is committed.
  sinks.clear();
  sinks.push_back(simbob::makeVideoSink((tmp.path / "dropped.avi").string(), 10, &err));
  async = simbob::makeAsyncSink(std::move(sinks), 4);
  for (int i = 0; i < 6; ++i) REQUIRE(async->add(movingSquares(160, 120, i)) == nullptr);
  async.reset();
  CHECK(entries(tmp.path) == 2);  // async.avi, direct.avi
}

TEST_CASE("probeVideo says why it cannot open a file", "[image][video]") {
  ImageTempDir tmp;
  simbob::VideoInfo info;
  const std::string missing = (tmp.path / "none.avi").string();
  Error e = simbob::probeVideo(missing, &info);
  CHECK(e.kind == ErrorKind::MissingInput);
  CHECK(e.str() == missing + ": No such file or directory");
  const std::string text = (tmp.path / "text.avi").string();
  std::ofstream(text) << "not a video";
  e = simbob::probeVideo(text, &info);
  CHECK(e.kind == ErrorKind::InvalidInput);
  CHECK(info.frames == 0);
}
