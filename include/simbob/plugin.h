// Plug-ins (guide 2, 3.3.1 ExtensionFolder, 9.2): shared libraries that add component types.
// A plug-in exports one C function, simbob_plugin_v1, returning a SimbobPluginV1 whose
// abi_version is SIMBOB_PLUGIN_ABI_VERSION; simbob calls its register_types with a PluginHost,
// through which it adds controller types to the same Registry as the built-ins. A plug-in
// controller's party is made by the plug-in's factory from the lowered ControllerDef and acts
// through World (simbob/physics.h), like the built-in controllers. The ABI is C++: a plug-in
// must be built with the same compiler and simbob headers as the simbob that loads it
// (docs/plugins.md); the version number changes whenever this header or the types it uses change.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simbob/model.h"
#include "simbob/registry.h"
#include "simbob/run.h"

#define SIMBOB_PLUGIN_ABI_VERSION 2u

namespace simbob {

// PluginPartyFactory (simbob/model.h) builds the party of one plug-in controller from its
// lowered definition: def.numbers holds the values of PluginControllerType::numbers in their
// order, def.actuators the Model::actuators index of each of PluginControllerType::refs in
// their order, def.period its Period (s).

/// A number parameter of a plug-in controller (a Value of type Number).
struct PluginNumber {
  std::string name;
  double default_value = 0;
  std::string unit;
  std::string doc;
};

/// A reference parameter: a Ref to a periphery that implements `interface` (RCDriver,
/// RCPosControl or RCVelControl).
struct PluginRef {
  std::string name;
  std::string interface;
  std::string doc;
};

/// A controller type a plug-in adds (family ControllerComponent).
struct PluginControllerType {
  std::string name;  ///< the type's element name; must not be taken (by a built-in or a plug-in)
  std::string doc;
  std::vector<PluginRef> refs;
  std::vector<PluginNumber> numbers;
  PluginPartyFactory make = nullptr;
};

/// The registry entry of a plug-in controller type: its refs, then Period (s, default 0.01),
/// then its numbers (lib/components/controllers.cpp). `type` must outlive the registry.
TypeSpec controllerTypeSpec(const PluginControllerType& type);

/// What register_types may call.
class PluginHost {
 public:
  virtual ~PluginHost();
  /// Adds a controller type; false (and the run stops with the reason) if its name is taken.
  virtual bool addController(const PluginControllerType& type) = 0;
};

}  // namespace simbob

extern "C" {

struct SimbobPluginV1 {
  uint32_t abi_version;  ///< SIMBOB_PLUGIN_ABI_VERSION of the headers it was built with
  const char* name;      ///< for messages
  /// Adds the plug-in's types through `host`; false if it could not.
  bool (*register_types)(simbob::PluginHost* host);
};

/// The entry point every plug-in defines.
const SimbobPluginV1* simbob_plugin_v1(void);
}
