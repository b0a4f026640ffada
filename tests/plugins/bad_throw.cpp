// A plug-in through simbob/plugin.hpp whose controller BadController throws: in its constructor
// (THROW_CREATE) or in act at t >= 0.5 s (THROW_ACT). The header catches both and hands simbob
// the message (tests/cli/plugins.sh).
#include <stdexcept>

#include "simbob/plugin.hpp"

namespace {

class Bad : public simbob::plugin::Controller {
 public:
  explicit Bad(const double*) {
#ifdef THROW_CREATE
    throw std::runtime_error("constructor failed on purpose");
#endif
  }
  void act(simbob::plugin::Host&, double t) override {
#ifdef THROW_ACT
    if (t >= 0.5) throw std::runtime_error("act failed on purpose");
#endif
    (void)t;
  }
};

}  // namespace

SIMBOB_PLUGIN("bad", simbob::plugin::controller<Bad>("BadController", "throws", {}, {}))
