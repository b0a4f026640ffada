// The urdfdom side of lib/urdf, built as a module of its own (libsimbob_urdf.so, urdf_module.h):
// urdf::parseURDF and console_bridge, the only parts of urdfdom that are not headers.
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <mutex>

#include "urdf_module.h"  // (relative: the Python module builds this file without lib/ on its path)

namespace simbob {

namespace {

/// urdfdom reports through console_bridge, process-wide: its messages are collected here while
/// one parse runs (under a lock) instead of going to stderr.
class Collect : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && first.empty()) first = text;
  }
  std::string first;
};

urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& text, std::string* message) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  Collect collect;
  console_bridge::useOutputHandler(&collect);
  const console_bridge::LogLevel level = console_bridge::getLogLevel();
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    collect.first = e.what();
    model.reset();
  }
  console_bridge::setLogLevel(level);
  console_bridge::restorePreviousOutputHandler();
  *message = collect.first;
  return model;
}

const UrdfModule kModule{kUrdfModuleAbi, parseWithUrdfdom};

}  // namespace

}  // namespace simbob

extern "C" const simbob::UrdfModule* simbob_urdf_module() { return &simbob::kModule; }
