// Loads plug-ins (docs/plugins.md): every --plugin FILE in command-line order, then every
// `.so` in the global setting ExtensionFolder in sorted order, each through its
// simbob_plugin_v2 entry point (simbob/plugin_c.h), adding its types to the one Registry before any scene is read.
#include "plugins.h"

#include <algorithm>
#include <filesystem>

#include "cli.h"
#include "simbob/plugin.h"

namespace simbob::cli {

namespace {

int loadOne(Registry& reg, const std::string& path) {
  Error e;
  if (!loadPluginLibrary(reg, path, &e)) {
    g_log.error(e);
    return exitCodeFor(e.kind);
  }
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
