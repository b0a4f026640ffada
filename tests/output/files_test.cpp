// lib/output/files.cpp: the one whole-file reader (scenes, imports, settings, trajectories).
#include "simbob/tool/files.h"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace fs = std::filesystem;
using simbob::readFile;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("simbob_files_test_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& bytes) const {
    const fs::path p = path / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p.string();
  }
};

}  // namespace

TEST_CASE("readFile reads whole files and says why it cannot", "[output][files]") {
  TempDir dir;
  std::string text = "stale", why;

  // Every byte, including NULs and CR LF, unchanged.
  const std::string bytes("a\0b\r\n\xff", 6);
  CHECK(readFile(dir.write("a.bin", bytes), 100, &text, &why));
  CHECK(text == bytes);
  CHECK(readFile(dir.write("empty", ""), 100, &text, &why));
  CHECK(text.empty());

  // Exactly at the cap is fine, one byte more is not.
  const std::string path = dir.write("ten", "0123456789");
  CHECK(readFile(path, 10, &text, &why));
  CHECK_FALSE(readFile(path, 9, &text, &why));
  CHECK(text.empty());
  CHECK(why == "larger than 0 MiB");
  CHECK_FALSE(readFile(dir.write("big", std::string((size_t{1} << 20) + 1, 'x')), size_t{1} << 20, &text, &why));
  CHECK(why == "larger than 1 MiB");

  // A device that never ends stops at the cap instead of eating the memory.
  CHECK_FALSE(readFile("/dev/zero", size_t{2} << 20, &text, &why));
  CHECK(why == "larger than 2 MiB");

  CHECK_FALSE(readFile((dir.path / "missing").string(), 100, &text, &why));
  CHECK(why == "No such file or directory");
  CHECK_FALSE(readFile(dir.path.string(), 100, &text, &why));
  CHECK(why == "Is a directory");
  CHECK_FALSE(readFile(dir.path.string(), 100, &text, nullptr));  // the reason is optional
}
