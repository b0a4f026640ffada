// Deliberately wrong plug-ins for tests/cli/plugins.sh, one per compile definition:
// BAD_ABI (abi_version 999), DUPLICATE (registers RCDriveTest, a built-in's name), NO_ENTRY
// (no simbob_plugin_v1), and plug-ins whose code fails, each adding the controller type
// BadController (no parameters but Period) that misbehaves in one place:
// THROW_REGISTER (register_types throws), THROW_MAKE (the party's constructor throws),
// NULL_MAKE (make returns null), THROW_FIRST (first() throws), THROW_GRANT (onGrant throws
// at t >= 0.5 s), BAD_INDEX (setCommand(99999) at t >= 0.5 s), NEG_INDEX (setCommand(-1)).
#include <memory>
#include <stdexcept>

#include "simbob/physics.h"
#include "simbob/plugin.h"

#ifndef NO_ENTRY
namespace {

#if defined(BAD_ABI) || defined(DUPLICATE)
std::unique_ptr<simbob::Party> make(const simbob::ControllerDef&) { return nullptr; }

bool registerTypes(simbob::PluginHost* host) {
  simbob::PluginControllerType t;
  t.name = "RCDriveTest";
  t.make = make;
  return host->addController(t);
}
#else
class Bad : public simbob::Party {
 public:
  Bad() {
#ifdef THROW_MAKE
    throw std::runtime_error("constructor failed on purpose");
#endif
  }
  simbob::SimTime first() override {
#ifdef THROW_FIRST
    throw std::runtime_error("first failed on purpose");
#endif
    return 0;
  }
  simbob::SimTime onGrant(simbob::SimTime now, simbob::World& world) override {
    if (now >= 500000000) {
#ifdef THROW_GRANT
      throw std::runtime_error("onGrant failed on purpose");
#elif defined(BAD_INDEX)
      world.setCommand(99999, 1.0);
#elif defined(NEG_INDEX)
      world.setCommand(-1, 1.0);
#endif
    }
    (void)world;
    return now + 10000000;  // every 0.01 s
  }
};

std::unique_ptr<simbob::Party> make(const simbob::ControllerDef&) {
#ifdef NULL_MAKE
  return nullptr;
#else
  return std::make_unique<Bad>();
#endif
}

bool registerTypes(simbob::PluginHost* host) {
#ifdef THROW_REGISTER
  throw std::runtime_error("register_types failed on purpose");
#endif
  simbob::PluginControllerType t;
  t.name = "BadController";
  t.make = make;
  return host->addController(t);
}
#endif

#ifdef BAD_ABI
const SimbobPluginV1 kPlugin{999, "bad_abi", registerTypes};
#elif defined(DUPLICATE)
const SimbobPluginV1 kPlugin{SIMBOB_PLUGIN_ABI_VERSION, "duplicate", registerTypes};
#else
const SimbobPluginV1 kPlugin{SIMBOB_PLUGIN_ABI_VERSION, "bad", registerTypes};
#endif

}  // namespace

extern "C" const SimbobPluginV1* simbob_plugin_v1(void) { return &kPlugin; }
#else
extern "C" int not_a_plugin(void) { return 1; }
#endif
