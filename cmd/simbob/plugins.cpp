// Loads plug-ins (docs/plugins.md): every --plugin FILE in command-line order, then every
// `.so` in the global setting ExtensionFolder in sorted order, each through its
// simbob_plugin_v1 entry point, adding its types to the one Registry before any scene is read.
#include "plugins.h"

#include <dlfcn.h>

#include <algorithm>
#include <deque>
#include <exception>
#include <filesystem>

#include "cli.h"
#include "simbob/plugin.h"

namespace simbob::cli {

namespace {

/// Plug-in types and libraries live as long as the process: the registry points at the types
/// and parties run the plug-ins' code (never dlclose'd).
std::deque<PluginControllerType>& keptTypes() {
  static std::deque<PluginControllerType> types;
  return types;
}

class Host : public PluginHost {
 public:
  Host(Registry& reg, std::string plugin) : reg_(reg), plugin_(std::move(plugin)) {}
  bool addController(const PluginControllerType& type) override {
    keptTypes().push_back(type);
    if (!type.make) {
      problem_ = "controller type '" + type.name + "' has no party factory (make)";
      return false;
    }
    TypeSpec spec = controllerTypeSpec(keptTypes().back());
    spec.plugin_name = plugin_;  // run-time errors of its parties name the plug-in
    if (reg_.add(std::move(spec))) return true;
    problem_ = reg_.problems().back();
    return false;
  }
  const std::string& problem() const { return problem_; }

 private:
  Registry& reg_;
  std::string plugin_;
  std::string problem_;
};

int loadOne(Registry& reg, const std::string& path) {
  auto fail = [&](ErrorKind kind, const std::string& what) {
    g_log.error({kind, {path, 0}, what});
    return exitCodeFor(kind);
  };
  // RTLD_NOW: a missing symbol is an error here, not a crash in the middle of a run.
  void* lib = dlopen(path.find('/') == std::string::npos ? ("./" + path).c_str() : path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char* e = dlerror();
    return fail(ErrorKind::MissingInput, std::string("cannot load the plug-in: ") + (e ? e : "dlopen failed"));
  }
  void* sym = dlsym(lib, "simbob_plugin_v1");
  if (!sym)
    return fail(ErrorKind::InvalidInput,
                "not a simbob plug-in: it has no entry point simbob_plugin_v1 (see simbob/plugin.h)");
  using Entry = const SimbobPluginV1* (*)();
  // Every call into a plug-in is guarded: an exception is an error naming the library (65).
  auto threw = [&](const std::string& call, const char* what) {
    return fail(ErrorKind::InvalidInput,
                call + " threw" +
                    (what ? std::string(": ") + what : std::string(" an exception that is not a std::exception")));
  };
  const SimbobPluginV1* p = nullptr;
  try {
    p = reinterpret_cast<Entry>(sym)();  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  } catch (const std::exception& e) {
    return threw("simbob_plugin_v1()", e.what());
  } catch (...) {
    return threw("simbob_plugin_v1()", nullptr);
  }
  if (!p) return fail(ErrorKind::InvalidInput, "simbob_plugin_v1 returned null");
  if (p->abi_version != SIMBOB_PLUGIN_ABI_VERSION)
    return fail(ErrorKind::InvalidInput,
                "plug-in ABI version " + std::to_string(p->abi_version) + ", but this simbob loads version " +
                    std::to_string(SIMBOB_PLUGIN_ABI_VERSION) + " (rebuild it against this simbob's headers)");
  const std::string name = p->name ? p->name : "?";
  Host host(reg, name);
  bool registered = false;
  try {
    registered = p->register_types && p->register_types(&host);
  } catch (const std::exception& e) {
    return threw("plug-in '" + name + "': register_types", e.what());
  } catch (...) {
    return threw("plug-in '" + name + "': register_types", nullptr);
  }
  if (!registered)
    return fail(ErrorKind::InvalidInput, std::string("plug-in '") + (p->name ? p->name : "?") +
                                             "' could not register its types" +
                                             (host.problem().empty() ? std::string() : ": " + host.problem()));
  g_log.debug("loaded plug-in " + path);
  return 0;
}

}  // namespace

int loadPlugins(Registry& reg, const std::vector<std::string>& files, const std::string& folder) {
  for (const std::string& f : files)
    if (int c = loadOne(reg, f)) return c;
  if (folder.empty()) return 0;
  std::error_code ec;
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(folder, ec))
    if (e.path().extension() == ".so") found.push_back(e.path().string());
  if (ec) {
    g_log.error({ErrorKind::MissingInput, {folder, 0}, "cannot read ExtensionFolder: " + ec.message()});
    return kExitNoInput;
  }
  std::sort(found.begin(), found.end());
  for (const std::string& f : found)
    if (int c = loadOne(reg, f)) return c;
  return 0;
}

}  // namespace simbob::cli
