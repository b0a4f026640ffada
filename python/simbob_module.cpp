// `import simbob`: the Python module over the Simulation API (include/simbob/simulation.h).
// One Python Simulation owns one simbob::Simulation; arrays are numpy copies of the state at the
// current grid instant; errors become simbob.Error subclasses, one per exit-status class of the
// CLI, carrying kind, file, line and message. Python controllers are parties of the run, granted
// on the same clock as the scene's controllers.
#include <pybind11/functional.h>
#include <pybind11/eval.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simbob/clock.h"
#include "simbob/error.h"
#include "simbob/overrides.h"
#include "simbob/physics.h"
#include "simbob/plugin.h"
#include "simbob/registry.h"
#include "simbob/renderer.h"
#include "simbob/loop.h"
#include "simbob/scene_run.h"
#include "simbob/simulation.h"

namespace py = pybind11;

namespace {

using simbob::Error;
using simbob::ErrorKind;
using simbob::SimTime;

// The last instant of simbob's clock (SimTime counts nanoseconds in an int64; kNever, 2**63 - 1
// ns, means never): a step or run_until beyond it is refused, never wrapped to a negative time.
constexpr SimTime kClockEnd = simbob::kNever - 1;
const char* const kClockEndText = "9.223372036854775807e9";

// The one registry of component types, built at import (as `main` builds the CLI's); plug-ins
// add to it (load_plugin). Never destroyed: compiled models may point at its types until the
// interpreter ends.
simbob::Registry& registry() {
  static simbob::Registry* reg = [] {
    auto* r = new simbob::Registry;
    if (!simbob::registerBuiltins(*r))
      throw std::runtime_error("simbob: the built-in component types did not register");
    return r;
  }();
  return *reg;
}

// ---- errors ----

// The exception classes, defined in Python (readable help(), keyword construction) at import.
const char* const kErrorClasses = R"PY(
class Error(Exception):
    """An error of simbob, as the command line reports it.

    Attributes:
        kind (str): the error's kind: "InvalidInput", "MissingInput", "CannotCreate",
            "IoError", "Diverged", "Interrupted", "ControllerFailed", "Internal",
            "Unavailable", "Protocol" or "Usage".
        file (str or None): the file the error is about (a scene file, or "override TEXT"
            for an override), None when it is about no file.
        line (int or None): the 1-based line in that file, None when unknown.
        message (str): what went wrong, without the place.
        exit_status (int): the status `simbob run` exits with for this kind (sysexits.h).

    str(e) is the command line's one-line form: "file:line: error: message".
    """

    exit_status = 70

    def __init__(self, message, kind="Internal", file=None, line=None):
        self.message = message
        self.kind = kind
        self.file = file
        self.line = line
        super().__init__(self.__str__())

    def __str__(self):
        place = self.file if self.file else "simbob"
        if self.file and self.line:
            place += ":" + str(self.line)
        return place + ": error: " + self.message


class SceneError(Error):
    """The scene or a value in it is wrong (kind "InvalidInput"; exit status 65)."""
    exit_status = 65


class MissingInputError(Error):
    """An input file does not exist or cannot be read (kind "MissingInput"; exit status 66)."""
    exit_status = 66


class UsageError(Error):
    """An argument that cannot be used: an unknown actuator, a bad override or step (kind "Usage"; exit status 64)."""
    exit_status = 64


class DivergedError(Error):
    """The run diverged: a non-finite or runaway state, or a joint that came apart (kind
    "Diverged"; exit status 1)."""
    exit_status = 1


class ControllerError(Error):
    """A controller failed the run: a plug-in (controller, sensor or actuator) reported an error
    or misused the API, or a controller threw (kind "ControllerFailed"; exit status 2). The
    failures of socket peers are its subclasses UnavailableError and ProtocolError. A Python
    controller's own exception propagates as itself instead."""
    exit_status = 2


class RunInterrupted(Error, KeyboardInterrupt):
    """The run was asked to stop (SIGINT or SIGTERM; kind "Interrupted"; exit status 130/143).
    A KeyboardInterrupt too, so `except KeyboardInterrupt` catches it."""
    exit_status = 130


class UnavailableError(ControllerError):
    """A party held the simulation past MaxAccessTime, or a socket peer never connected, went
    away or fell silent (kind "Unavailable"; exit status 69)."""
    exit_status = 69


class OutputError(Error):
    """An output cannot be created or written (kinds "CannotCreate" 73, "IoError" 74)."""
    exit_status = 74


class ProtocolError(ControllerError):
    """A socket peer sent a line the protocol does not allow (kind "Protocol"; exit status 76)."""
    exit_status = 76


class InternalError(Error):
    """A bug in simbob (kind "Internal"; exit status 70)."""
    exit_status = 70
)PY";

// The module, borrowed: a static py::object would be released after the interpreter ended.
py::handle& thisModule() {
  static py::handle m;
  return m;
}

const char* kindName(ErrorKind k) {
  switch (k) {
    case ErrorKind::InvalidInput:
      return "InvalidInput";
    case ErrorKind::MissingInput:
      return "MissingInput";
    case ErrorKind::CannotCreate:
      return "CannotCreate";
    case ErrorKind::IoError:
      return "IoError";
    case ErrorKind::Diverged:
      return "Diverged";
    case ErrorKind::Interrupted:
      return "Interrupted";
    case ErrorKind::ControllerFailed:
      return "ControllerFailed";
    case ErrorKind::Internal:
      return "Internal";
    case ErrorKind::Unavailable:
      return "Unavailable";
    case ErrorKind::Protocol:
      return "Protocol";
    case ErrorKind::Usage:
      return "Usage";
  }
  return "Internal";
}

const char* className(ErrorKind k) {
  switch (k) {
    case ErrorKind::InvalidInput:
      return "SceneError";
    case ErrorKind::MissingInput:
      return "MissingInputError";
    case ErrorKind::CannotCreate:
    case ErrorKind::IoError:
      return "OutputError";
    case ErrorKind::Diverged:
      return "DivergedError";
    case ErrorKind::Interrupted:
      return "RunInterrupted";
    case ErrorKind::ControllerFailed:
      return "ControllerError";
    case ErrorKind::Internal:
      return "InternalError";
    case ErrorKind::Unavailable:
      return "UnavailableError";
    case ErrorKind::Protocol:
      return "ProtocolError";
    case ErrorKind::Usage:
      return "UsageError";
  }
  return "InternalError";
}

// Raises e as its simbob.Error subclass (the GIL must be held).
[[noreturn]] void raiseError(const Error& e, py::object errors = py::none()) {
  py::object cls = thisModule().attr(className(e.kind));
  py::object file = e.loc.file.empty() ? py::object(py::none()) : py::object(py::str(e.loc.file.str()));
  py::object line = e.loc.line > 0 ? py::object(py::int_(e.loc.line)) : py::object(py::none());
  py::object exc = cls(e.message, kindName(e.kind), file, line);
  if (!errors.is_none()) exc.attr("errors") = errors;
  PyErr_SetObject(cls.ptr(), exc.ptr());
  throw py::error_already_set();
}

[[noreturn]] void raiseUsage(const std::string& message) { raiseError(Error{ErrorKind::Usage, {}, message}); }

// Load errors: a missing input wins (nothing behind it could be checked, as the CLI decides);
// otherwise the first. Every error's one-line form goes into the exception's `errors`.
[[noreturn]] void raiseDiagnostics(const simbob::Diagnostics& diag) {
  if (diag.errors().empty())
    raiseError(Error{ErrorKind::Internal, {}, "the scene could not be loaded (no reason given)"});
  const Error* chosen = &diag.errors().front();
  for (const Error& e : diag.errors())
    if (e.kind == ErrorKind::MissingInput) {
      chosen = &e;
      break;
    }
  py::list all;
  for (const Error& e : diag.errors()) {
    std::string place = e.loc.file.empty() ? std::string("simbob") : e.loc.file.str();
    if (!e.loc.file.empty() && e.loc.line > 0) place += ":" + std::to_string(e.loc.line);
    all.append(place + ": error: " + e.message);
  }
  raiseError(*chosen, all);
}

/// A path argument (str, bytes or os.PathLike) as a string. A NUL in it is refused: the C calls
/// underneath would read the path only up to it, and open another file without a word.
std::string pathArg(const py::object& path, const char* what) {
  const std::string p = py::module_::import("os").attr("fspath")(path).cast<std::string>();
  if (p.find('\0') != std::string::npos)
    raiseUsage(std::string(what) + " " + py::repr(path).cast<std::string>() +
               " holds a NUL character, which no file name can hold");
  return p;
}

// ---- overrides: a dict {"KEY.PARAM": value} or a list of "KEY.PARAM=VALUE" ----

std::string valueText(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) return py::repr(v).cast<std::string>();
  if (py::isinstance<py::sequence>(v)) {  // a vector: "0 0 1"
    std::string out;
    for (const py::handle& x : v.cast<py::sequence>()) out += (out.empty() ? "" : " ") + valueText(x);
    return out;
  }
  return py::str(v).cast<std::string>();
}

std::vector<simbob::Override> parseOverrides(const py::object& overrides) {
  std::vector<std::string> texts;
  if (overrides.is_none()) return {};
  if (py::isinstance<py::dict>(overrides)) {
    for (const auto& kv : overrides.cast<py::dict>())
      texts.push_back(py::str(kv.first).cast<std::string>() + "=" + valueText(kv.second));
  } else if (py::isinstance<py::str>(overrides)) {
    raiseUsage("overrides: expected a dict or a list of \"KEY.PARAM=VALUE\" strings, got one string");
  } else {
    for (const py::handle& t : overrides.cast<py::sequence>()) {
      if (!py::isinstance<py::str>(t))
        raiseUsage("overrides: expected \"KEY.PARAM=VALUE\" strings, got " + py::repr(t).cast<std::string>());
      texts.push_back(t.cast<std::string>());
    }
  }
  std::vector<simbob::Override> out;
  for (const std::string& t : texts) {
    simbob::Override o;
    std::string why;
    if (!simbob::parseOverride(t, &o, &why)) raiseUsage("override: " + why);
    o.place = "override " + o.text;
    out.push_back(std::move(o));
  }
  return out;
}

// ---- the Python Simulation ----

class PySimulation;

// add_controller(period, fn): granted at t = 0, period, 2 period, ... (whole nanoseconds, as the
// built-in periodic controllers), each grant at the first grid instant at or after its time.
// fn(sim) runs with the GIL held (step() keeps it while a Python controller is attached); an
// exception from fn stops the run and step() re-raises it.
class PyController : public simbob::Party {
 public:
  PyController(PySimulation* owner, py::handle sim, SimTime period, py::function fn, std::string what,
               simbob::SourceLoc where)
      : owner_(owner), sim_(sim), period_(period), fn_(std::move(fn)) {
    name = std::move(what);
    loc = std::move(where);
  }
  SimTime first() override;
  SimTime onGrant(SimTime now, simbob::World&) override {
    try {
      fn_(sim_);
    } catch (py::error_already_set& e) {
      pending_ = std::make_unique<py::error_already_set>(std::move(e));
      failure_ = Error{ErrorKind::ControllerFailed, loc, name + " raised " + oneLine(*pending_)};
      return simbob::kNever;
    } catch (const std::exception& e) {
      failure_ = Error{ErrorKind::ControllerFailed, loc, name + " failed: " + e.what()};
      return simbob::kNever;
    }
    return nextAfter(now);
  }
  const Error* failure() const override { return failure_ ? &*failure_ : nullptr; }
  /// The Python exception fn raised, once (null if none).
  std::unique_ptr<py::error_already_set> takePending() { return std::move(pending_); }

 private:
  /// "ValueError: the first line of its message", or the class alone ("KeyboardInterrupt"): the
  /// run's error says it again at every later call, in one line (no traceback).
  static std::string oneLine(const py::error_already_set& e) {
    std::string out = "an exception";
    try {
      out = py::str(e.type().attr("__name__")).cast<std::string>();
      std::string text = e.value() && !e.value().is_none() ? py::str(e.value()).cast<std::string>() : "";
      text = text.substr(0, text.find('\n'));
      if (!text.empty()) out += ": " + text;
    } catch (...) {  // NOLINT(bugprone-empty-catch): a class or message that cannot be read leaves the default
    }
    return out;
  }

  SimTime nextAfter(SimTime now) const {
    const SimTime k = now / period_ + 1;
    return k > simbob::kNever / period_ ? simbob::kNever : k * period_;
  }

  PySimulation* owner_;
  py::handle sim_;  // borrowed: the Python Simulation owns this party
  SimTime period_;
  py::function fn_;
  std::unique_ptr<py::error_already_set> pending_;
  std::optional<Error> failure_;
};

// The threads keyword (--threads): None is 1.
int threadCount(const py::object& threads) {
  if (threads.is_none()) return 0;
  const int n = threads.cast<int>();
  if (n < 1 || n > simbob::kMaxThreads)
    raiseUsage("threads must be between 1 and " + std::to_string(simbob::kMaxThreads) + ", got " +
               py::repr(threads).cast<std::string>());
  return n;
}

class PySimulation {
 public:
  PySimulation(const std::string& scene, const py::object& overrides, uint32_t seed, const py::object& dt,
               const py::object& threads, const std::string* text) {
    simbob::SimulationOptions opts;
    opts.overrides = parseOverrides(overrides);
    opts.seed = seed;
    opts.threads = threadCount(threads);
    if (!dt.is_none()) {
      const py::object real = py::module_::import("numbers").attr("Real");
      double h = std::nan("");
      if (!py::isinstance<py::bool_>(dt) && py::isinstance(dt, real)) {
        try {
          h = py::float_(dt).cast<double>();
        } catch (py::error_already_set&) {  // OverflowError of an int beyond a double: out of range below
        }
      }
      if (!(h >= 1e-9 && h <= 1e9))
        raiseUsage("dt must be a number of seconds from 1e-9 to 1e9, got " + py::repr(dt).cast<std::string>());
      opts.dt = h;
    }
    simbob::Diagnostics diag;
    if (text) {
      sim_ = simbob::Simulation::fromText(*text, scene, registry(), opts, diag);
    } else {
      sim_ = simbob::Simulation::fromFile(scene, registry(), opts, diag);
    }
    if (!sim_) raiseDiagnostics(diag);
    for (const Error& w : diag.warnings()) {
      std::string place = w.loc.file.empty() ? std::string("simbob") : w.loc.file.str();
      if (!w.loc.file.empty() && w.loc.line > 0) place += ":" + std::to_string(w.loc.line);
      warnings_.push_back(place + ": warning: " + w.message);
    }
    scene_ = scene;
    check(sim_->running());
  }

  // One thread at a time: another thread's call while a step runs (the GIL released) is
  // refused; a Python controller's calls during the step (same thread) may read and command.
  class Busy {
   public:
    Busy(PySimulation& s, bool reads_only) : s_(s) {
      std::thread::id none;
      const std::thread::id me = std::this_thread::get_id();
      if (s_.owner_.compare_exchange_strong(none, me)) {
        owns_ = true;
        return;
      }
      if (none != me)
        raiseUsage("this Simulation is in use by another thread: use one Simulation from one thread at a time");
      if (!reads_only)
        raiseUsage("a controller may read the state and set commands, not step, reset or add controllers");
    }
    bool owns() const { return owns_; }
    ~Busy() {
      if (owns_) s_.owner_ = std::thread::id();
    }
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

   private:
    PySimulation& s_;
    bool owns_ = false;
  };

  simbob::Simulation& sim() { return *sim_; }

  void step(uint64_t n) {
    Busy b(*this, false);
    // The clock counts nanoseconds in 63 bits: refuse what would pass its end (the time would
    // wrap to a negative one), before anything moves.
    const SimTime now = sim_->now(), h = stepNs();
    const uint64_t room = static_cast<uint64_t>((kClockEnd - now) / h);
    if (n > room)
      raiseUsage("step(" + std::to_string(n) + "): the time would pass " + kClockEndText +
                 " s (2**63 ns), the end of simbob's clock: at most " + std::to_string(room) + " more steps of " +
                 simbob::formatNumber(sim_->stepSize()) + " s from t=" + simbob::formatNumber(sim_->time()) + " s");
    check(stepSliced(n));
  }

  void runUntil(double t) {
    if (!std::isfinite(t)) raiseUsage("run_until: the time must be finite, got " + simbob::formatNumber(t));
    if (!simbob::toSimTime(t) || *simbob::toSimTime(t) > kClockEnd)
      raiseUsage("run_until: t=" + simbob::formatNumber(t) + " s is beyond the end of simbob's clock (" +
                 kClockEndText + " s: 2**63 ns)");
    Busy b(*this, false);
    check(runUntilSliced(t));
  }

  // The parties due at the current instant are served first (step(0), as step() would), so the
  // command applies after them: at t = 0 before the first step too. From a controller (already
  // within the serving of this instant) it applies at once.
  void setCommand(int actuator, double value) {
    Busy b(*this, true);
    if (b.owns()) check(sim_->step(0));
    const Error e = sim_->setCommand(actuator, value);
    if (!e.message.empty()) raiseError(e);
  }

  void reset(uint32_t seed) {
    Busy b(*this, false);
    for (PyController* c : controllers_) c->takePending();
    renderers_.clear();  // a moving camera starts again with the run
    check(sim_->reset(seed));
  }

  /// The scene at the current instant through the renderer of `simbob render` and Record: one
  /// renderer (GL context) per camera, size and quality, kept so that a moving camera follows
  /// the frames drawn before, as in a recording.
  py::array_t<uint8_t> render(const std::string& camera, int width, int height, const std::string& quality) {
    Busy b(*this, true);
    simbob::RenderOptions ro;
    ro.camera = camera;
    ro.width = width;
    ro.height = height;
    if (!quality.empty() && !simbob::parseQuality(quality, &ro.quality))
      raiseUsage("unknown quality '" + quality + "' (frame, wire, plane, flat, smooth, textures, shadows, " +
                 "transparency, fog)");
    if (width < 1 || height < 1 || width > simbob::kMaxImageSide || height > simbob::kMaxImageSide)
      raiseUsage("size must be 1 to " + std::to_string(simbob::kMaxImageSide) + " pixels a side");
    const simbob::Model& model = sim_->model();
    const std::string key =
        camera + "\n" + std::to_string(width) + "x" + std::to_string(height) + "\n" + simbob::qualityName(ro.quality);
    auto it = renderers_.find(key);
    if (it == renderers_.end()) {
      Error err;
      std::unique_ptr<simbob::Renderer> r = simbob::Renderer::create(model, ro, &err);
      if (!r) raiseError(err);
      it = renderers_.emplace(key, std::move(r)).first;
    }
    const simbob::World& w = sim_->world();
    std::vector<simbob::Transform> poses(static_cast<size_t>(w.bodyCount()));
    for (int i = 0; i < w.bodyCount(); ++i) poses[static_cast<size_t>(i)] = w.body(i).pose;
    simbob::Image img;
    if (const Error* e = it->second->render(poses, sim_->time(), &img)) raiseError(*e);
    py::array_t<uint8_t> a({img.height, img.width, 3});
    std::memcpy(a.mutable_data(), img.rgb.data(), img.rgb.size());
    return a;
  }

  void addController(py::handle self, double period, py::function fn) {
    Busy b(*this, false);
    const std::optional<SimTime> p = std::isfinite(period) && period > 0 ? simbob::toSimTime(period) : std::nullopt;
    if (!p || *p < 1 || *p > kClockEnd)
      raiseUsage("add_controller: the period must be from 1e-9 s to " + std::string(kClockEndText) +
                 " s (the clock's range), got " + simbob::formatNumber(period));
    // Named after fn and placed where add_controller was called, for the run's messages.
    std::string what = "Python controller";
    if (py::hasattr(fn, "__qualname__")) what += " '" + py::str(fn.attr("__qualname__")).cast<std::string>() + "'";
    simbob::SourceLoc where;
    py::object frame = py::module_::import("sys").attr("_getframe")(0);
    where.file = py::str(frame.attr("f_code").attr("co_filename")).cast<std::string>();
    where.line = frame.attr("f_lineno").cast<int>();
    auto c = std::make_unique<PyController>(this, self, *p, std::move(fn), std::move(what), std::move(where));
    controllers_.push_back(c.get());
    sim_->addParty(std::move(c));
  }

  const std::vector<std::string>& warnings() const { return warnings_; }
  const std::string& scene() const { return scene_; }

  /// The run's step in ns (whole: the clock's grid).
  SimTime stepNs() const { return std::max<SimTime>(1, *simbob::toSimTime(sim_->stepSize())); }

  // A long call runs in slices of about 10 ms of wall-clock time, so that Ctrl-C (SIGINT,
  // Python's KeyboardInterrupt) stops it at a grid instant with the run usable from there:
  // between slices the GIL is taken back (when it was released) and Python's signal handlers run;
  // an exception from them is raised from the call. Slicing does not change the run: step(a)
  // then step(b) is step(a + b), and runUntil through earlier instants reaches the instant
  // runUntil alone does (docs/python.md).
  using Wall = std::chrono::steady_clock;
  /// Steps in the first slice: a short call (step(37)) is one slice, as it was one call.
  static constexpr uint64_t kFirstSlice = 32;

  /// f() with the GIL released unless a Python controller needs it.
  template <class F>
  bool unlocked(F f) {
    if (!controllers_.empty()) return f();
    py::gil_scoped_release nogil;
    return f();
  }

  /// Between two slices: the next slice aims at about 10 ms; Python's signal handlers run.
  static void betweenSlices(Wall::time_point start, uint64_t* slice) {
    const double took = std::chrono::duration<double>(Wall::now() - start).count();
    if (took < 0.005 && *slice < (uint64_t{1} << 40)) *slice *= 2;
    if (took > 0.02 && *slice > 1) *slice /= 2;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }

  bool stepSliced(uint64_t n) {
    uint64_t slice = kFirstSlice;
    while (true) {
      const uint64_t k = std::min(n, slice);
      const Wall::time_point start = Wall::now();
      if (!unlocked([&] { return sim_->step(k); })) return false;
      n -= k;
      if (n == 0) return true;
      betweenSlices(start, &slice);
    }
  }

  bool runUntilSliced(double t) {
    uint64_t slice = kFirstSlice;
    while (true) {
      const double next = sim_->time() + static_cast<double>(slice) * sim_->stepSize();
      if (!(next < t)) return unlocked([&] { return sim_->runUntil(t); });
      const Wall::time_point start = Wall::now();
      if (!unlocked([&] { return sim_->runUntil(next); })) return false;
      betweenSlices(start, &slice);
    }
  }

  // Raises the run's stop: a Python controller's exception as it was, else the run's error.
  void check(bool ok) {
    if (ok) return;
    for (PyController* c : controllers_)
      if (auto e = c->takePending()) {
        py::error_already_set err = std::move(*e);
        throw err;
      }
    raiseError(sim_->result().error);
  }

 private:
  std::unique_ptr<simbob::Simulation> sim_;
  std::vector<PyController*> controllers_;  // owned by sim_
  std::vector<std::string> warnings_;
  std::string scene_;
  std::atomic<std::thread::id> owner_{};                                // the thread using it now (none: free)
  std::map<std::string, std::unique_ptr<simbob::Renderer>> renderers_;  // after sim_: they read its model
};

SimTime PyController::first() {
  pending_.reset();  // a new run (reset) starts clean
  failure_.reset();
  const SimTime now = owner_->sim().now();  // 0 while the world is being built
  const SimTime k = now / period_ + (now % period_ != 0 ? 1 : 0);
  return k > simbob::kNever / period_ ? simbob::kNever : k * period_;
}

// Guards a read against a step running on another thread.
struct ReadGuard {
  explicit ReadGuard(PySimulation& s) : busy(s, true) {}
  PySimulation::Busy busy;
};

py::array_t<double> matrix(size_t rows, size_t cols) {
  return py::array_t<double>(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
}

template <typename Defs>
std::vector<std::string> keysOf(const Defs& defs) {
  std::vector<std::string> out;
  out.reserve(defs.size());
  for (const auto& d : defs) out.push_back(d.key);
  return out;
}

int actuatorIndex(PySimulation& s, const py::object& key) {
  const auto& acts = s.sim().model().actuators;
  if (py::isinstance<py::str>(key)) {
    const std::string k = key.cast<std::string>();
    const int i = s.sim().actuator(k);
    if (i >= 0) return i;
    std::string list;
    for (const auto& a : acts) list += (list.empty() ? "" : ", ") + a.key;
    raiseUsage("no actuator '" + simbob::quoteInput(k) + "' in " + s.scene() +
               (list.empty() ? " (it has none)" : " (its actuators: " + list + ")"));
  }
  if (py::isinstance<py::int_>(key) && !py::isinstance<py::bool_>(key)) {
    int overflow = 0;  // an int beyond 64 bits (2**70) is out of range too, not a bare RuntimeError
    const long long i = PyLong_AsLongLongAndOverflow(key.ptr(), &overflow);
    if (overflow != 0 || i < 0 || i >= static_cast<long long>(acts.size()))
      raiseUsage("no actuator " + py::str(key).cast<std::string>() + " (the scene has " + std::to_string(acts.size()) +
                 ")");
    return static_cast<int>(i);
  }
  raiseUsage("set_command: an actuator is a key (str) or an index (int), got " + py::repr(key).cast<std::string>());
}

int sensorIndex(PySimulation& s, const std::string& key) {
  const int i = s.sim().sensor(key);
  if (i >= 0) return i;
  std::string list;
  for (const auto& d : s.sim().model().sensors) list += (list.empty() ? "" : ", ") + d.key;
  raiseUsage("no sensor '" + simbob::quoteInput(key) + "' in " + s.scene() +
             (list.empty() ? " (it has none)" : " (its sensors: " + list + ")"));
}

// ---- simbob.run(): a whole run through the Run, writing exactly the files `simbob run` writes ----

std::string pathText(const py::object& p) { return py::module_::import("os").attr("fspath")(p).cast<std::string>(); }

// The view of a recording: size "WxH" or (w, h), camera key, quality level.
void recordingView(const py::object& size, const std::string& camera, const std::string& quality,
                   simbob::RenderOptions* ro) {
  if (!size.is_none()) {
    int w = 0, h = 0;
    if (py::isinstance<py::str>(size)) {
      const std::string t = size.cast<std::string>();
      char x = 0;
      if (std::sscanf(t.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x') w = h = 0;
    } else {
      const py::sequence wh = size.cast<py::sequence>();
      if (wh.size() == 2) {
        w = wh[0].cast<int>();
        h = wh[1].cast<int>();
      }
    }
    if (w < 1 || h < 1 || w > simbob::kMaxImageSide || h > simbob::kMaxImageSide)
      raiseUsage("size must be \"WIDTHxHEIGHT\" or (width, height) with 1 to " + std::to_string(simbob::kMaxImageSide) +
                 " pixels each, got " + py::repr(size).cast<std::string>());
    ro->width = w;
    ro->height = h;
  }
  ro->camera = camera;
  if (!quality.empty() && !simbob::parseQuality(quality, &ro->quality))
    raiseUsage("unknown quality '" + quality + "' (frame, wire, plane, flat, smooth, textures, shadows, " +
               "transparency, fog)");
}

// Ctrl-C during a long run: Python would see the signal only once the run returned, so while
// simbob.run() runs on the main thread SIGINT sets a stop flag instead, as `simbob run`'s
// handler does: the run ends at the next step and keeps its partial outputs, and Python's own
// handler is back before RunInterrupted (a KeyboardInterrupt) is raised.
volatile std::sig_atomic_t g_py_stop = 0;

class StopOnSigint {
 public:
  StopOnSigint() {
    g_py_stop = 0;
    const bool main_thread = py::module_::import("threading")
                                 .attr("current_thread")()
                                 .is(py::module_::import("threading").attr("main_thread")());
    if (!main_thread) return;  // signals reach the main thread's Python only
    struct sigaction sa {};
    sa.sa_handler = [](int) { g_py_stop = 1; };
    sigemptyset(&sa.sa_mask);
    installed_ = ::sigaction(SIGINT, &sa, &old_) == 0;
  }
  ~StopOnSigint() {
    if (installed_) ::sigaction(SIGINT, &old_, nullptr);
  }
  StopOnSigint(const StopOnSigint&) = delete;
  StopOnSigint& operator=(const StopOnSigint&) = delete;

 private:
  struct sigaction old_ {};
  bool installed_ = false;
};

py::dict pyRun(const py::object& scene, double duration, const py::object& out, const py::object& overrides,
               uint32_t seed, const py::object& dt, double sample_interval, const std::string& log,
               const py::object& log_out, const std::string& columns, const py::object& record, const py::object& video,
               const py::object& html, const py::object& size, const std::string& camera, const std::string& quality,
               double fps, bool check_determinism, const py::object& controllers, double peer_timeout, int port_offset,
               const py::object& threads) {
  simbob::RunOptions o;
  o.scene = pathText(scene);
  o.simulation.duration = duration;
  o.simulation.overrides = parseOverrides(overrides);
  o.simulation.seed = seed;
  if (!dt.is_none()) o.simulation.dt = dt.cast<double>();
  o.sample_interval = sample_interval;
  if (!out.is_none()) o.out = pathText(out);
  if (!log.empty()) {
    std::string problem;
    if (!simbob::parseRunLogWhat(log, &o.log, &problem)) raiseUsage("log: " + problem);
  }
  if (!log_out.is_none()) o.log_out = pathText(log_out);
  if (columns != "pose" && columns != "pose,velocity")
    raiseUsage("columns must be \"pose\" or \"pose,velocity\", got '" + columns + "'");
  o.velocity_columns = columns == "pose,velocity";
  if (!record.is_none()) o.record = pathText(record);
  if (!video.is_none()) o.video = pathText(video);
  if (!html.is_none()) o.html = pathText(html);
  recordingView(size, camera, quality, &o.render);
  o.fps = fps;
  if (!(fps > 0 && fps <= 1000))
    raiseUsage("fps must be above 0 and at most 1000, got " + py::repr(py::float_(fps)).cast<std::string>());
  o.check_determinism = check_determinism;
  if (!controllers.is_none())
    for (const auto& kv : controllers.cast<py::dict>())
      o.simulation.controllers.push_back(
          py::str(kv.first).cast<std::string>() + "=" +
          (kv.second.is_none() ? std::string() : py::str(kv.second).cast<std::string>()));
  o.simulation.peer_timeout = peer_timeout;
  o.simulation.port_offset = port_offset;
  o.simulation.threads = threadCount(threads);
  o.simulation.stop = &g_py_stop;
  std::vector<std::string> errors, warnings;
  simbob::RunListener listener;
  listener.note = [&](const simbob::RunNote& n) {
    if (n.level == simbob::RunNote::Warning) warnings.push_back(n.what.str());
    if (n.level == simbob::RunNote::Error) errors.push_back(n.what.errorLine());
  };
  Error refusal;
  std::unique_ptr<simbob::Run> run;
  simbob::RunOutcome outcome;
  {
    StopOnSigint sigint;  // Python's handler is back before any Python code runs again
    py::gil_scoped_release nogil;
    run = simbob::Run::open(o, registry(), listener, &refusal);
    if (run) outcome = run->finish();
  }
  if (!run) {
    py::list all;
    for (const std::string& e : errors) all.append(e);
    raiseError(refusal, all);
  }
  py::object warn = py::module_::import("warnings").attr("warn");
  for (const std::string& w : warnings) warn(w, py::module_::import("builtins").attr("RuntimeWarning"), 2);
  if (outcome.output_error) raiseError(*outcome.output_error);
  if (outcome.result.status != simbob::RunStatus::Completed) raiseError(outcome.result.error);
  py::object json = py::module_::import("json");
  return json.attr("loads")(outcome.summary.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

}  // namespace

PYBIND11_MODULE(_simbob, m) {
  thisModule() = m.ptr();
  m.doc() = R"(simbob: headless robot simulation (Simulator Bob scenes on ODE) from Python.

Load a scene, step it on its fixed step grid, read the state as numpy arrays, set actuator
commands, and attach Python controllers that run on the same clock as the scene's own::

    import simbob
    sim = simbob.Simulation("scenes/pendulum.xml", seed=0)
    sim.run_until(1.0)
    print(sim.time, sim.body_keys, sim.poses())

Same scene, overrides and seed give the same numbers, bit for bit, as `simbob run`.
Errors are simbob.Error subclasses carrying kind, file, line and message.)";
  m.attr("__version__") = SIMBOB_VERSION;
  py::exec(kErrorClasses, m.attr("__dict__"));
  for (const char* name : {"Error", "SceneError", "MissingInputError", "UsageError", "DivergedError", "ControllerError",
                           "RunInterrupted", "UnavailableError", "OutputError", "ProtocolError", "InternalError"})
    m.attr(name).attr("__module__") = "simbob";
  registry();
  m.def(
      "load_plugin",
      [](const py::object& path) {
        const std::string p = pathArg(path, "load_plugin: the path");
        Error e;
        if (!simbob::loadPluginLibrary(registry(), p, &e)) raiseError(e);
      },
      py::arg("path"),
      R"(Loads a plug-in library (docs/plugins.md) as `simbob --plugin` does: its controller, sensor
and actuator types join the registry for every scene loaded after. Raises simbob.MissingInputError
when the file cannot be loaded and simbob.SceneError when it is not a simbob plug-in of this ABI
or its type names are taken (loading it twice included).)");

  m.def("run", &pyRun, py::arg("scene"), py::kw_only(), py::arg("duration"), py::arg("out") = py::none(),
        py::arg("overrides") = py::none(), py::arg("seed") = 0, py::arg("dt") = py::none(),
        py::arg("sample_interval") = 0.01, py::arg("log") = "", py::arg("log_out") = py::none(),
        py::arg("columns") = "pose", py::arg("record") = py::none(), py::arg("video") = py::none(),
        py::arg("html") = py::none(), py::arg("size") = py::none(), py::arg("camera") = "", py::arg("quality") = "",
        py::arg("fps") = 30.0, py::arg("check_determinism") = false, py::arg("controllers") = py::none(),
        py::arg("peer_timeout") = 10.0, py::arg("port_offset") = 0, py::arg("threads") = py::none(),
        R"(Runs a scene to `duration` s and writes what `simbob run` writes, byte for byte: the
trajectory CSV (`out`, default the scene's name with .csv in the current folder), its summary
(.json beside it), the controllers' log, and, when asked, the run log, the recording and the
replay page. The same object runs both (the library's Run), so options, defaults, checks,
messages and outputs are the CLI's.

Args mirror `simbob run`'s options: overrides (--set, as for Simulation), seed, dt, sample_interval,
log ("joints,sensors,commands") and log_out, columns ("pose" or "pose,velocity"), record (a
folder of PNG frames), video (.avi or .mp4), html (the replay page), size ("640x480" or (w, h)),
camera, quality and fps of the recording, check_determinism, controllers ({"KEY": "COMMAND"},
as --controller), peer_timeout, port_offset, threads (None: 1).

Returns the run summary as a dict. The scene's warnings go to Python's warnings (RuntimeWarning).

Raises:
    SceneError, MissingInputError, UsageError, OutputError: refused before it started
        (e.errors lists every error line); nothing is written then.
    DivergedError, ControllerError (UnavailableError, ProtocolError), RunInterrupted (a
        KeyboardInterrupt): the run stopped; like `simbob run`, it kept what it computed as
        .partial files beside its outputs, named in its .partial.json summary.)");

  py::class_<PySimulation> cls(m, "Simulation",
                               R"(One run of a scene: its compiled model, its world, the clock on the fixed step
grid and the parties that drive it (the scene's controllers, Python controllers).

The world advances only in whole steps of `dt`. At every grid instant it reaches, the
parties due there are served first (the scene's controllers in scene order, then Python
controllers in the order added); between calls you read the state and set commands. A
command set between calls applies from the current instant on. Arrays are fresh numpy
float64 copies of the state at the current instant, bodies/joints/actuators/sensors in
the order of `body_keys`, `joint_keys`, `actuator_keys`, `sensor_keys` (document order).

Use one Simulation from one thread at a time (another thread's call during a step raises
UsageError). Any number of Simulations may live in one process; each gives the same
numbers as it would alone.)");

  cls.def(py::init([](const py::object& scene, const py::object& overrides, uint32_t seed, const py::object& dt,
                      const py::object& threads) {
            const std::string path = pathArg(scene, "the scene path");
            return std::make_unique<PySimulation>(path, overrides, seed, dt, threads, nullptr);
          }),
          py::arg("scene"), py::arg("overrides") = py::none(), py::arg("seed") = 0, py::arg("dt") = py::none(),
          py::arg("threads") = py::none(),
          R"(Loads, checks and compiles a scene file and builds its world at t = 0.

Args:
    scene (str | os.PathLike): the scene file (XML, or INI when it ends in .ini).
    overrides (dict | list[str] | None): scene parameters to change before compiling, as
        `simbob run --set` does: {"Crate.Material.Friction": 0.3} or
        ["Crate.Material.Friction=0.3"]. Dict values are written as in the scene file
        (numbers with repr(), sequences joined with spaces, bools as true/false).
    seed (int): the state ODE's random generator starts from (QuickStep's constraint
        order), 0 to 2**32-1, as `simbob run --seed`.
    dt (float | None): the step in s; None takes the scene's MaxTimeStep.
    threads (int | None): threads a step may use, 1 to 64, as `simbob run --threads`; every
        count gives the same numbers. None is 1.

Raises:
    SceneError: the scene is wrong (e.file, e.line point at the first error; e.errors
        lists every error's one-line form).
    MissingInputError: the file (or a file it imports) cannot be read.
    UsageError: a malformed override, a dt outside 1e-9 to 1e9 s or threads outside 1 to 64.

The scene's warnings (`simbob check`'s) are in `warnings`.)");
  cls.def_static(
      "from_text",
      [](const std::string& text, const py::object& name, const py::object& overrides, uint32_t seed,
         const py::object& dt, const py::object& threads) {
        return std::make_unique<PySimulation>(pathArg(name, "from_text: the name"), overrides, seed, dt, threads,
                                              &text);
      },
      py::arg("text"), py::arg("name") = "scene.xml", py::arg("overrides") = py::none(), py::arg("seed") = 0,
      py::arg("dt") = py::none(), py::arg("threads") = py::none(),
      R"(The same as Simulation(...) from scene text in memory. `name` stands for the file
in messages and is where relative imports are looked up from; a name ending in .ini reads
the text as INI, anything else as XML.)");

  cls.def(
      "step", [](PySimulation& s, uint64_t n) { s.step(n); }, py::arg("n") = 1,
      R"(Serves the parties due at the current instant, then takes n whole steps of dt, serving
the parties due at each instant reached. After step(n) from t, time is t + n dt.

Raises DivergedError when the run diverges (a non-finite or runaway state, a joint that came
apart); the exception a Python controller raised, as it was; another simbob.Error when a
party stops the run. A stopped run raises its error again at every later step until
reset(). Without a Python controller the GIL is released while stepping.)");
  cls.def(
      "run_until", [](PySimulation& s, double t) { s.runUntil(t); }, py::arg("t"),
      R"(Steps to the first grid instant at or after t (s), serving the parties on the way.
Does nothing when that instant is the current one or behind it. Raises as step() does.)");
  cls.def(
      "reset", [](PySimulation& s, uint32_t seed) { s.reset(seed); }, py::arg("seed") = 0,
      R"(Back to t = 0 with a fresh world and fresh scene controllers, seeded with `seed`. Python
controllers stay and are granted again from t = 0. The same numbers as a new Simulation with
that seed and the same controllers.)");
  cls.def(
      "add_controller",
      [](py::object self, double period, py::function fn) {
        self.cast<PySimulation&>().addController(self, period, std::move(fn));
      },
      py::arg("period"), py::arg("fn"),
      R"(Attaches fn(sim) as a controller granted every `period` s: at t = 0, period, 2 period, ...
(whole nanoseconds; each at the first grid instant at or after it), after the scene's
controllers due at the same instant, on the same clock, so a run with Python controllers is
as deterministic as any other. Added mid-run, it starts at the first multiple of period at or
after the current time. fn reads the state and sets commands through sim (it must not step
it). It runs with the GIL held: while a Python controller is attached, step() and run_until()
keep the GIL. An exception from fn stops the run; step() re-raises it.)");

  cls.def_property_readonly(
      "time", [](PySimulation& s) { return s.sim().time(); },
      "The current simulated time (s): steps * dt on the nanosecond grid.");
  cls.def_property_readonly(
      "steps", [](PySimulation& s) { return s.sim().steps(); }, "The number of whole steps taken since t = 0.");
  cls.def_property_readonly(
      "dt", [](PySimulation& s) { return s.sim().stepSize(); },
      "The step taken (s): dt or the scene's MaxTimeStep, on the nanosecond grid.");
  cls.def_property_readonly(
      "scene", [](PySimulation& s) { return s.scene(); }, "The scene file (or text name) this was loaded from.");
  cls.def_property_readonly(
      "warnings", [](PySimulation& s) { return s.warnings(); },
      "The scene's warnings as one-line strings \"file:line: warning: message\" (load and `simbob check`).");
  cls.def_property_readonly(
      "physics_messages",
      [](PySimulation& s) {
        const simbob::PhysicsMessages m = s.sim().world().physicsMessages();
        py::dict d;
        d["count"] = m.count;
        d["first"] = m.first;
        d["first_time"] = m.first_time;
        return d;
      },
      "What ODE reported while stepping so far, as the run summary's physics_messages: count, first "
      "(one line) and first_time (the end of the step it came in, s); count 0 when nothing.");
  cls.def_property_readonly(
      "running", [](PySimulation& s) { return s.sim().running(); },
      "False once the run has stopped (diverged, failed): only reset() continues it.");
  cls.def_property_readonly(
      "body_keys", [](PySimulation& s) { return keysOf(s.sim().model().bodies); },
      "Fully qualified keys of the mobile bodies (the CSV's), in the order of poses() rows.");
  cls.def_property_readonly(
      "joint_keys", [](PySimulation& s) { return keysOf(s.sim().model().joints); },
      "Fully qualified keys of the joints, in the order of joint_positions().");
  cls.def_property_readonly(
      "actuator_keys", [](PySimulation& s) { return keysOf(s.sim().model().actuators); },
      "Fully qualified keys of the actuators (drives, servos, velocity drives), in the order of commands().");
  cls.def_property_readonly(
      "sensor_keys", [](PySimulation& s) { return keysOf(s.sim().model().sensors); },
      "Fully qualified keys of the sensors (every kind), in the order of touching().");
  cls.def_property_readonly(
      "programs",
      [](PySimulation& s) {
        std::vector<std::string> out;
        for (const simbob::SocketDef& d : s.sim().model().sockets)
          if (!d.controller.empty()) out.push_back(d.key);
        return out;
      },
      R"(Keys of the RCLocalSocketCommunicators whose Controller program this Simulation started
(a child process, ended with the run or at reset()): the programs a scene runs.)");

  cls.def(
      "poses",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        const int n = w.bodyCount();
        auto a = matrix(static_cast<size_t>(n), 7);
        auto r = a.mutable_unchecked<2>();
        for (int i = 0; i < n; ++i) {
          const simbob::BodyState b = w.body(i);
          for (int k = 0; k < 3; ++k) r(i, k) = b.pose.p[static_cast<size_t>(k)];
          for (int k = 0; k < 4; ++k) r(i, 3 + k) = b.pose.q[static_cast<size_t>(k)];
        }
        return a;
      },
      R"(Body poses, numpy float64 (N, 7): x y z (m) and the unit quaternion qw qx qy qz, global
frame, at each body's origin; rows in body_keys order. The numbers `simbob run` writes.)");
  cls.def(
      "velocities",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        const int n = w.bodyCount();
        auto a = matrix(static_cast<size_t>(n), 6);
        auto r = a.mutable_unchecked<2>();
        for (int i = 0; i < n; ++i) {
          const simbob::BodyState b = w.body(i);
          for (int k = 0; k < 3; ++k) {
            r(i, k) = b.lin_vel[static_cast<size_t>(k)];
            r(i, 3 + k) = b.ang_vel[static_cast<size_t>(k)];
          }
        }
        return a;
      },
      R"(Body velocities, numpy float64 (N, 6): linear vx vy vz (m/s) of the body's origin and
angular wx wy wz (rad/s), both in the global frame; rows in body_keys order.)");
  cls.def(
      "joint_positions",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        py::array_t<double> a(w.jointCount());
        auto r = a.mutable_unchecked<1>();
        for (int i = 0; i < w.jointCount(); ++i) r(i) = w.joint(i).position;
        return a;
      },
      R"(Joint positions, numpy float64 (J,), in joint_keys order: a hinge's angle (rad, right-hand
rule about its axis; the total angle, unwrapped across turns), a slider's travel (m); 0 at the scene's start
pose; always 0 for ball-socket and fixed joints.)");
  cls.def(
      "joint_velocities",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        py::array_t<double> a(w.jointCount());
        auto r = a.mutable_unchecked<1>();
        for (int i = 0; i < w.jointCount(); ++i) r(i) = w.joint(i).velocity;
        return a;
      },
      "Joint velocities, numpy float64 (J,): rad/s (hinge) or m/s (slider); 0 for ball-socket and fixed joints.");
  cls.def(
      "touching",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        py::array_t<bool> a(w.sensorCount());
        auto r = a.mutable_unchecked<1>();
        for (int i = 0; i < w.sensorCount(); ++i) r(i) = w.touching(i);
        return a;
      },
      R"(Sensors, numpy bool (S,) in sensor_keys order: whether the proximity sensor touches another
body (static geoms included, its own body and the bodies jointed to it not) now; False for
sensors of other kinds (read them with sensor()).)");
  cls.def(
      "sensor",
      [](PySimulation& s, const std::string& key) {
        ReadGuard g(s);
        const std::vector<double>& v = s.sim().world().sensorReading(sensorIndex(s, key));
        py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
        auto r = a.mutable_unchecked<1>();
        for (size_t i = 0; i < v.size(); ++i) r(static_cast<py::ssize_t>(i)) = v[i];
        return a;
      },
      py::arg("key"),
      R"(The reading of the sensor with this key now, numpy float64 (N,): its quantities in the
order of sensor_quantities(key) (docs/sensors.md): touching (0 or 1); distance (m); range0..
(m); ax ay az (m/s^2) gx gy gz (rad/s); ticks; a plug-in sensor's own quantities. Raises
simbob.UsageError for an unknown key.)");
  cls.def(
      "camera_image",
      [](PySimulation& s, const std::string& key) {
        ReadGuard g(s);
        const simbob::Image* img = s.sim().cameraImage(key);
        if (!img) {
          std::string list;
          for (const auto& d : s.sim().model().camera_sensors) list += (list.empty() ? "" : ", ") + d.key;
          raiseUsage("no camera sensor '" + simbob::quoteInput(key) + "' in " + s.scene() +
                     (list.empty() ? " (it has none)" : " (its camera sensors: " + list + ")"));
        }
        py::array_t<uint8_t> a({img->height, img->width, 3});
        if (!img->rgb.empty()) std::memcpy(a.mutable_data(), img->rgb.data(), img->rgb.size());
        return a;
      },
      py::arg("key"),
      R"(The latest image of the RCCameraSensor with this key, numpy uint8 (height, width, 3): RGB,
rows top first, drawn at t = 0, Period, 2 Period, ... (before the controllers there) and held in
between; (0, 0, 3) before the first instant is served (docs/sensors.md). Raises
simbob.UsageError for an unknown key.)");
  cls.def(
      "sensor_quantities",
      [](PySimulation& s, const std::string& key) {
        ReadGuard g(s);
        return s.sim().world().sensorQuantities(sensorIndex(s, key));
      },
      py::arg("key"), "Names of the quantities of sensor(key), in order (list of str).");
  cls.def(
      "commands",
      [](PySimulation& s) {
        ReadGuard g(s);
        const simbob::World& w = s.sim().world();
        py::array_t<double> a(w.actuatorCount());
        auto r = a.mutable_unchecked<1>();
        for (int i = 0; i < w.actuatorCount(); ++i) r(i) = w.command(i);
        return a;
      },
      R"(Actuator commands now, numpy float64 (A,) in actuator_keys order, as clamped by the limits:
a drive's voltage in [-1, 1], a servo's target position (m or rad), a velocity drive's target
velocity (m/s or rad/s). Before the first command: 0 (a servo: its start position).)");
  cls.def(
      "set_command",
      [](PySimulation& s, const py::object& key, double value) { s.setCommand(actuatorIndex(s, key), value); },
      py::arg("actuator"), py::arg("value"),
      R"(Commands an actuator from the current instant on, clamped by its limits as the scene's
controllers' commands are (see commands()). The parties due at the current instant are served
first (as step() would serve them), so the command applies after the scene's controllers
there, also at t = 0 before the first step; from a Python controller it applies at once. On a
run that has stopped it raises the run's error, as step() does. `actuator` is a key from actuator_keys or an
index into it. Raises UsageError for an unknown key, an index out of range or a value that is
not finite.)");
  cls.def(
      "render",
      [](PySimulation& s, const py::object& camera, const std::pair<int, int>& size, const std::string& quality) {
        return s.render(camera.is_none() ? std::string() : camera.cast<std::string>(), size.first, size.second,
                        quality);
      },
      py::arg("camera") = py::none(), py::arg("size") = std::make_pair(640, 480), py::arg("quality") = "",
      R"(The scene at the current instant as an image: numpy uint8 (h, w, 3), RGB, rows top first,
drawn off-screen by the same renderer as `simbob render` and `simbob run --record` (EGL, else
OSMesa: no display or GPU needed). `camera` is a camera key (default: the scene's first camera,
else a view that frames the bodies); `size` is (width, height) in pixels; `quality` one of
frame, wire, plane, flat, smooth, textures, shadows, transparency (the default), fog. A scene
whose models show no body is drawn as its collision shapes. Each camera, size and quality keeps
its renderer, so a tracking camera follows the frames drawn before (reset() starts it again).
Raises MissingInputError without a GL back end or for a missing texture, SceneError for a
camera key the scene does not have, UsageError for a bad size or quality.)");
  cls.def("__repr__", [](PySimulation& s) {
    return "<simbob.Simulation " + py::repr(py::str(s.scene())).cast<std::string>() +
           " t=" + py::repr(py::float_(s.sim().time())).cast<std::string>() +
           " bodies=" + std::to_string(s.sim().model().bodies.size()) + ">";
  });
}
