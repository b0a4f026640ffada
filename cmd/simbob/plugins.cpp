// Loads plug-ins (docs/plugins.md): every --plugin FILE in command-line order, then every
// `.so` in the global setting ExtensionFolder in sorted order, each through its
// simbob_plugin_v2 entry point (simbob/plugin_c.h), adding its types to the one Registry before any scene is read.
#include "plugins.h"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>

#include "cli.h"
#include "simbob/plugin.h"

namespace simbob::cli {

namespace {

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
  void* sym = dlsym(lib, "simbob_plugin_v2");
  if (!sym && dlsym(lib, "simbob_plugin_v1"))
    return fail(ErrorKind::InvalidInput,
                "built for plug-in ABI 1 (the C++ ABI, entry point simbob_plugin_v1), which this simbob no longer "
                "loads: rebuild it against simbob/plugin_c.h or simbob/plugin.hpp (docs/plugins.md)");
  if (!sym)
    return fail(ErrorKind::InvalidInput,
                "not a simbob plug-in: it has no entry point simbob_plugin_v2 (see simbob/plugin_c.h)");
  using Entry = const SimbobPlugin* (*)();
  const SimbobPlugin* p = reinterpret_cast<Entry>(sym)();  // NOLINT(cppcoreguidelines-pro-type-reinterpret-cast)
  if (!p) return fail(ErrorKind::InvalidInput, "simbob_plugin_v2 returned null");
  if (p->abi_version != SIMBOB_PLUGIN_ABI_VERSION)
    return fail(ErrorKind::InvalidInput, "plug-in ABI version " + std::to_string(p->abi_version) +
                                             ", but this simbob loads version " +
                                             std::to_string(SIMBOB_PLUGIN_ABI_VERSION) +
                                             " (rebuild it against this simbob's simbob/plugin_c.h)");
  const std::string problem = registerPlugin(reg, *p);
  if (!problem.empty())
    return fail(ErrorKind::InvalidInput,
                "plug-in '" + std::string(p->name ? p->name : "?") + "' could not register its types: " + problem);
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
