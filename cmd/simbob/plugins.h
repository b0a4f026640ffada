// Plug-in loading for the CLI (docs/plugins.md).
#pragma once

#include <string>
#include <vector>

namespace simbob {
class Registry;
}

namespace simbob::cli {

/// Loads each of `files`, then every *.so in `folder` ("" = none) in sorted order, adding their
/// types to `reg`. Returns 0, or the exit status after logging a one-line error naming the file:
/// 66 when it cannot be loaded, 65 when it is not a simbob plug-in, has another ABI version or
/// adds a type whose name is taken.
int loadPlugins(Registry& reg, const std::vector<std::string>& files, const std::string& folder);

}  // namespace simbob::cli
