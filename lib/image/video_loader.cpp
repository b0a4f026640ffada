// makeVideoSink, videoEncoderFor and probeVideo open libsimbob_video.so (FFmpeg) the first time
// they are called: beside the executable, one folder up (tests and benchmarks in the build tree),
// or in ../lib/simbob (an installed simbob). SIMBOB_VIDEO_MODULE names the file explicitly.
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "image/video_module.h"

namespace simbob {

namespace {

constexpr const char* kModuleName = "libsimbob_video.so";

std::string exeDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}

/// The module's table, or nullptr with `why` set.
const VideoModule* videoModule(std::string* why) {
  static std::once_flag once;
  static const VideoModule* module = nullptr;
  static std::string error;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("SIMBOB_VIDEO_MODULE"); env && *env) {
      candidates.emplace_back(env);
    } else {
      const std::string dir = exeDir();
      for (const char* rel : {"/", "/../", "/../lib/simbob/"}) candidates.push_back(dir + rel + kModuleName);
    }
    std::string tried;
    for (const std::string& path : candidates) {
      if (::access(path.c_str(), F_OK) != 0) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        error = std::string("cannot load the video module: ") + ::dlerror();
        return;
      }
      using Entry = const VideoModule* (*)();
      auto entry = reinterpret_cast<Entry>(::dlsym(handle, "simbob_video_module"));
      const VideoModule* m = entry ? entry() : nullptr;
      if (!m || m->abi != kVideoModuleAbi) {
        error = path + " is not this build's video module (simbob_video_module missing or of another ABI)";
        return;
      }
      module = m;
      return;
    }
    error = std::string("video output needs ") + kModuleName + " (FFmpeg), not found at " + tried;
  });
  if (!module && why) *why = error;
  return module;
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
