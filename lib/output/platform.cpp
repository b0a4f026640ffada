#include "simbob/tool/platform.h"

#include <dlfcn.h>
#include <gnu/libc-version.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

namespace simbob {

std::string compilerVersion() {
#ifdef __clang__
  return "clang " __clang_version__;
#else
  return "gcc " __VERSION__;
#endif
}

std::string libcVersion() { return std::string("glibc ") + gnu_get_libc_version(); }

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    const size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "unknown" : line.substr(start);
  }
  return "unknown";
}

namespace {
std::string exeDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : exe.parent_path().string();
}
}  // namespace

void* openSimbobModule(const char* file_name, const char* env, const char* entry, std::string* why) {
  std::vector<std::string> candidates;
  if (const char* e = std::getenv(env); e && *e) {
    candidates.emplace_back(e);
  } else {
    // Beside the program (the build tree; tests/ and bench/ hold links to the modules) and in an
    // installed simbob's lib/simbob. Never the folder above the program: for a simbob in
    // /tmp/x that is /tmp, where anyone can put a library whose constructor would run here.
    const std::string dir = exeDir();
    for (const char* rel : {"/", "/../lib/simbob/"}) candidates.push_back(dir + rel + file_name);
  }
  std::string tried;
  for (const std::string& path : candidates) {
    if (::access(path.c_str(), F_OK) != 0) {
      tried += (tried.empty() ? "" : ", ") + path;
      continue;
    }
    // A module that any user can write, or replace in its folder, is not opened (its constructor
    // would run before any check of what it is).
    struct stat file {
    }, folder{};
    const std::string dir = std::filesystem::path(path).parent_path().string();
    if (::stat(path.c_str(), &file) == 0 && ::stat(dir.empty() ? "." : dir.c_str(), &folder) == 0 &&
        ((file.st_mode & S_IWOTH) != 0 || (folder.st_mode & S_IWOTH) != 0)) {
      *why = path + " is not opened: " + ((file.st_mode & S_IWOTH) != 0 ? "it" : "its folder") +
             " can be written by any user";
      return nullptr;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      *why = std::string("cannot load ") + file_name + ": " + ::dlerror();
      return nullptr;
    }
    void* symbol = ::dlsym(handle, entry);
    if (!symbol) *why = path + " is not one of simbob's modules (" + entry + " missing)";
    return symbol;
  }
  *why = std::string(file_name) + " not found at " + tried;
  return nullptr;
}

}  // namespace simbob
