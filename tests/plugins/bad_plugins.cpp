// Deliberately wrong plug-ins for tests/cli/plugins.sh, one per compile definition:
// BAD_ABI (abi_version 999), DUPLICATE (registers RCDriveTest, a built-in's name), NO_ENTRY
// (no simbob_plugin_v1).
#include <memory>

#include "simbob/plugin.h"

#ifndef NO_ENTRY
namespace {

std::unique_ptr<simbob::Party> make(const simbob::ControllerDef&) { return nullptr; }

bool registerTypes(simbob::PluginHost* host) {
  simbob::PluginControllerType t;
  t.name = "RCDriveTest";
  t.make = make;
  return host->addController(t);
}

#ifdef BAD_ABI
const SimbobPluginV1 kPlugin{999, "bad_abi", registerTypes};
#else
const SimbobPluginV1 kPlugin{SIMBOB_PLUGIN_ABI_VERSION, "duplicate", registerTypes};
#endif

}  // namespace

extern "C" const SimbobPluginV1* simbob_plugin_v1(void) { return &kPlugin; }
#else
extern "C" int not_a_plugin(void) { return 1; }
#endif
