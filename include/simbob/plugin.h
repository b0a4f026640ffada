// simbob's side of plug-ins (docs/plugins.md): how the types a plug-in lists through the C ABI
// (simbob/plugin_c.h, the only header a plug-in needs) enter the Registry. The loader (the CLI,
// the Python module) finds the entry point simbob_plugin_v2 and hands its SimbobPlugin to
// registerPlugin; scenes then use the types like built-ins: controllers lower to
// ControllerDef::Plugin, sensors to SensorKind::Plugin, actuators to ActuatorDef::Plugin, each
// keeping a pointer to the plug-in's SimbobType (static storage in the library, never unloaded).
#pragma once

#include <string>
#include <vector>

#include "simbob/error.h"
#include "simbob/plugin_c.h"

namespace simbob {

class Registry;

/// A number parameter of a plug-in type (a Value of type Number).
struct PluginNumber {
  std::string name;
  double default_value = 0;
  std::string unit;
  std::string doc;
};

/// A controller's reference parameter: a Ref to a periphery that offers `interface`.
struct PluginRef {
  std::string name;
  std::string interface;
  std::string doc;
};

/// A plug-in's type as simbob keeps it: the C description copied into C++ values, checked.
struct PluginType {
  const SimbobType* c = nullptr;  ///< the plug-in's own description (lives as long as the process)
  std::string plugin;             ///< SimbobPlugin::name, for messages
  std::string name, doc, interface;
  std::vector<PluginNumber> numbers;
  std::vector<PluginRef> refs;          ///< controllers
  std::vector<std::string> quantities;  ///< sensors
};

/// "plug-in 'p', type 'T'", for messages.
std::string pluginWho(const std::string& plugin, const std::string& type);

/// Checks a plug-in's description (its version must be SIMBOB_PLUGIN_ABI_VERSION) and adds its
/// types to `reg`, in order. Returns "" or the first problem in words (a type whose name is
/// taken, a description that is incomplete), after which the registry may hold the types before
/// it. The types are kept for the process's lifetime.
std::string registerPlugin(Registry& reg, const SimbobPlugin& plugin);

/// Loads the plug-in library `path` (dlopen; a name without '/' is taken relative to the working
/// directory) and registers its types (registerPlugin). False with *error set, one line placed at
/// `path`: MissingInput when it cannot be loaded (exit 66), InvalidInput when it is not a simbob
/// plug-in, speaks another ABI (the C++ ABI's simbob_plugin_v1 included) or cannot register its
/// types (65). A library is never unloaded.
bool loadPluginLibrary(Registry& reg, const std::string& path, Error* error);

}  // namespace simbob
