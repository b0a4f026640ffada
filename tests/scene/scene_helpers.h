// Shared helpers of the scene tests: loading from text, temporary directories for imports,
// and a structural comparison of two component graphs.
#pragma once

#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_registry.h"
#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/registry.h"

namespace scenetest {

using namespace simbob;

/// All error lines of a Diagnostics, one per line (for INFO and substring checks).
inline std::string errorText(const Diagnostics& d) {
  std::string s;
  for (const auto& e : d.errors()) s += e.str() + "\n";
  return s;
}

inline bool loadText(const std::string& text, Scene* scene, Diagnostics& diag, Format format = Format::Xml,
                     const std::string& name = "test.xml") {
  return loadSceneFromText(text, name, format, testRegistry(), scene, diag);
}

/// Load text that must be valid; fails the test with the messages otherwise.
inline Scene mustLoad(const std::string& text, Format format = Format::Xml, const std::string& name = "test.xml") {
  Scene s;
  Diagnostics d;
  bool ok = loadText(text, &s, d, format, name);
  INFO(errorText(d));
  REQUIRE(ok);
  REQUIRE(d.errors().empty());
  return s;
}

/// Load and compile; both must succeed.
inline Model mustCompile(const std::string& text, Format format = Format::Xml, const std::string& name = "test.xml") {
  Scene s = mustLoad(text, format, name);
  Model m;
  Diagnostics d;
  bool ok = compileScene(s, &m, d);
  INFO(errorText(d));
  REQUIRE(ok);
  return m;
}

/// The component with fully qualified key `qkey`; fails the test if absent.
inline const Component& comp(const Scene& s, const std::string& qkey) {
  const int i = s.find(qkey);
  INFO("qualified key '" << qkey << "'");
  REQUIRE(i >= 0);
  return s.at(i);
}

/// A fresh directory under the system temp directory, removed on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = std::filesystem::temp_directory_path() /
            ("simbob_scene_test_" + std::to_string(stamp) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  /// Write `text` to `rel` (creating directories); returns the full path.
  std::string write(const std::string& rel, const std::string& text) const {
    std::filesystem::path p = path_ / rel;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream f(p, std::ios::binary);
    f << text;
    return p.string();
  }

 private:
  std::filesystem::path path_;
};

inline std::string readText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline bool sameLink(const Link& a, const Link& b) { return a.comp == b.comp && a.ref == b.ref && a.macro == b.macro; }

/// Structural equality of two graphs (everything but source locations and file lists).
inline void requireSameGraph(const Scene& a, const Scene& b) {
  REQUIRE(a.comps.size() == b.comps.size());
  CHECK(a.settings == b.settings);
  REQUIRE(a.components.size() == b.components.size());
  for (size_t i = 0; i < a.components.size(); ++i) CHECK(sameLink(a.components[i], b.components[i]));
  REQUIRE(a.cameras.size() == b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) CHECK(sameLink(a.cameras[i], b.cameras[i]));
  CHECK(a.sortedKeys() == b.sortedKeys());
  for (const std::string& k : a.sortedKeys()) CHECK(a.find(k) == b.find(k));
  for (size_t i = 0; i < a.comps.size(); ++i) {
    const Component& x = a.comps[i];
    const Component& y = b.comps[i];
    INFO("component " << i << " '" << x.qkey << "' (" << x.type->name << ")");
    REQUIRE(x.type == y.type);
    CHECK(x.key() == y.key());
    CHECK(x.has_key == y.has_key);
    CHECK(x.qkey == y.qkey);
    CHECK(x.parent == y.parent);
    CHECK(x.imported == y.imported);
    REQUIRE(x.slots.size() == y.slots.size());
    for (size_t p = 0; p < x.slots.size(); ++p) {
      INFO("parameter " << x.type->params[p].name);
      const Slot& s = x.slots[p];
      const Slot& t = y.slots[p];
      CHECK(s.set == t.set);
      CHECK(s.value() == t.value());
      CHECK(sameLink(s.link(), t.link()));
      REQUIRE(s.list().size() == t.list().size());
      for (size_t k = 0; k < s.list().size(); ++k) CHECK(sameLink(s.list()[k], t.list()[k]));
    }
  }
}

}  // namespace scenetest
