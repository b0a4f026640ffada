// The Simulation API (include/simbob/simulation.h): loading, the parties of a run in their
// order, and stepping through the Runner of lib/loop.
#include "simbob/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "simbob/compile.h"
#include "simbob/tool/files.h"
#include "simbob/robot.h"
#include "simbob/values.h"
#include "simulation/camera_sensors.h"

namespace simbob {

namespace {

// The one load path (loadModel) with `simbob check`'s warnings for the step the run will take.
std::unique_ptr<Simulation> loaded(const std::string& path, const std::string* text, const Registry& reg,
                                   const SimulationOptions& opts, Diagnostics& diag) {
  LoadRequest req;
  req.path = path;
  req.text = text;
  req.overrides = opts.overrides;
  req.lint = true;
  req.dt = opts.dt;
  LoadReport report;
  Model model;
  const bool ok = loadModel(req, reg, &model, &report);
  for (const Error& e : report.diagnostics.errors()) diag.error(e.loc, e.message, e.kind);
  for (const Error& w : report.diagnostics.warnings()) diag.warning(w.loc, w.message);
  return ok ? Simulation::fromModel(std::move(model), opts, diag) : nullptr;
}

/// Where the controller's log would overwrite one of its inputs -- the program (words[0], found
/// on PATH as execvp does) or a file named on its command line, both as seen from the folder it
/// runs in -- what that input is; else "".
std::string controllerLogClash(const SocketDef& d) {
  std::vector<std::string> words;
  std::string problem;
  if (d.controller_log.empty() || !splitCommandLine(d.controller, &words, &problem)) return "";
  auto inFolder = [&](const std::string& w) {
    return w.empty() || w[0] == '/' || d.controller_dir.empty() ? w : d.controller_dir + "/" + w;
  };
  const char* env_path = std::getenv("PATH");
  const std::string path = env_path ? env_path : "";
  for (size_t i = 0; i < words.size(); ++i) {
    std::vector<std::string> places = {inFolder(words[i])};
    if (i == 0 && words[0].find('/') == std::string::npos && env_path) {
      places.clear();
      for (size_t at = 0;;) {
        const size_t colon = path.find(':', at);
        const std::string dir = path.substr(at, colon == std::string::npos ? std::string::npos : colon - at);
        places.push_back(inFolder((dir.empty() ? "." : dir) + "/" + words[0]));
        if (colon == std::string::npos) break;
        at = colon + 1;
      }
    }
    for (const std::string& p : places)
      if (sameExistingFile(p, d.controller_log))
        return (i == 0 ? "the controller program " : "a file on the controller's command line ") + quoteInput(p, 400);
  }
  return "";
}

}  // namespace

std::string controllerFolder(const SocketDef& d) {
  std::error_code ec;
  const std::filesystem::path dir =
      d.controller_dir.empty() ? std::filesystem::current_path(ec) : std::filesystem::absolute(d.controller_dir, ec);
  return ec ? d.controller_dir : dir.lexically_normal().string();
}

Simulation::Simulation(Model model, SimulationOptions opts) : model_(std::move(model)), opts_(std::move(opts)) {}

Simulation::~Simulation() {
  runner_.reset();  // it points at the parties below
}

const Image* Simulation::cameraImage(const std::string& key) const { return cameras_ ? cameras_->image(key) : nullptr; }

std::unique_ptr<Simulation> Simulation::fromFile(const std::string& path, const Registry& reg,
                                                 const SimulationOptions& opts, Diagnostics& diag) {
  return loaded(path, nullptr, reg, opts, diag);
}

std::unique_ptr<Simulation> Simulation::fromText(const std::string& text, const std::string& name, const Registry& reg,
                                                 const SimulationOptions& opts, Diagnostics& diag) {
  return loaded(name, &text, reg, opts, diag);
}

std::unique_ptr<Simulation> Simulation::fromModel(Model model, const SimulationOptions& opts, Diagnostics& diag) {
  const double dt = resolvedStep(opts.dt, model.settings.max_time_step);
  if (!clockTimeProblem("", dt).empty()) {
    diag.error({}, "the step " + formatNumber(dt) + " s is outside 1e-9 to 1e9 s");
    return nullptr;
  }
  if (!(opts.duration >= 0 && opts.duration <= kMaxClockTime)) {
    diag.error({}, "the duration " + formatNumber(opts.duration) + " s is outside 0 to 1e9 s");
    return nullptr;
  }
  for (SocketDef& d : model.sockets) {
    d.timeout = opts.peer_timeout;
    if (d.port + opts.port_offset < 1 || d.port + opts.port_offset > 65535) {
      diag.error(d.loc,
                 "RCLocalSocketCommunicator '" + d.key + "': Port " + std::to_string(d.port) + " + --port-offset " +
                     std::to_string(opts.port_offset) + " is outside 1 to 65535",
                 ErrorKind::Usage);
      return nullptr;
    }
    d.port += opts.port_offset;
  }
  for (const std::string& option : opts.controllers) {
    const size_t eq = option.find('=');
    if (eq == std::string::npos || eq == 0) {
      diag.error({}, "--controller takes KEY=COMMAND, got '" + option + "'", ErrorKind::Usage);
      return nullptr;
    }
    const std::string key = option.substr(0, eq), command = option.substr(eq + 1);
    auto it =
        std::find_if(model.sockets.begin(), model.sockets.end(), [&](const SocketDef& d) { return d.key == key; });
    std::vector<std::string> words;
    std::string problem;
    if (it == model.sockets.end())
      problem = "no RCLocalSocketCommunicator has the key '" + key + "'" +
                (model.sockets.empty() ? " (the scene has none)" : " (the scene has '" + model.sockets[0].key + "')");
    else if (!command.empty() && !splitCommandLine(command, &words, &problem))
      problem = "RCLocalSocketCommunicator '" + key + "': --controller: " + problem;
    if (!problem.empty()) {
      diag.error({}, problem, ErrorKind::Usage);
      return nullptr;
    }
    it->controller = command;
    it->controller_dir.clear();  // relative to where simbob runs, as any path on its command line
  }
  for (const SocketDef& d : model.sockets)
    if (opts.no_controllers && !d.controller.empty()) {
      diag.error(d.loc,
                 "RCLocalSocketCommunicator '" + d.key + "' would start the program '" + quoteInput(d.controller, 400) +
                     "' in " + quoteInput(controllerFolder(d), 400) + ": --no-controllers refuses it (--controller " +
                     d.key + "= runs the scene with a peer of your own)",
                 ErrorKind::Usage);
      return nullptr;
    }
  const long started = std::count_if(model.sockets.begin(), model.sockets.end(),
                                     [](const SocketDef& d) { return !d.controller.empty(); });
  for (SocketDef& d : model.sockets)
    if (!d.controller.empty() && !opts.controller_log.empty())
      d.controller_log = started > 1 ? opts.controller_log + "." + d.key : opts.controller_log;
  for (const SocketDef& d : model.sockets) {
    const std::string input = controllerLogClash(d);
    if (input.empty()) continue;
    // Controller programs and their files are inputs: the log is never opened over one.
    diag.error(d.loc,
               "RCLocalSocketCommunicator '" + d.key + "': its controller's log " + quoteInput(d.controller_log, 400) +
                   " is " + input + ": an output must not overwrite an input",
               ErrorKind::Usage);
    return nullptr;
  }
  std::unique_ptr<Simulation> sim(new Simulation(std::move(model), opts));
  if (!sim->model_.camera_sensors.empty()) {
    Error err;
    sim->cameras_ = CameraSensors::create(sim->model_, sim->opts_, &err);
    if (!sim->cameras_) {
      diag.error(err.loc, err.message, err.kind);
      return nullptr;
    }
  }
  return sim;
}

void Simulation::sampleTrajectory(TrajectoryWriter* writer, double interval,
                                  std::function<void(double, const double*)> on_sample) {
  sampling_ = true;
  writer_ = writer;
  sample_interval_ = interval;
  on_sample_ = std::move(on_sample);
}

void Simulation::addParty(std::unique_ptr<Party> party) {
  owned_.push_back(std::move(party));
  addParty(*owned_.back());
}

void Simulation::addParty(Party& party) {
  extra_.push_back(&party);
  if (runner_) runner_->addParty(party);
}

bool Simulation::start() {
  if (runner_) return runner_->running();
  std::vector<Party*> parties;
  sampler_.reset();
  if (sampling_) {
    const SimTime interval = std::max<SimTime>(toSimTime(sample_interval_).value_or(1), 1);
    const SimTime min_step = toSimTime(model_.settings.min_time_step).value_or(0);
    sampler_ = std::make_unique<TrajectorySampler>(static_cast<int>(model_.bodies.size()), interval, min_step, writer_,
                                                   on_sample_, model_.frames);
    sampler_->name = "the trajectory sampler";
    parties.push_back(sampler_.get());
  }
  for (SocketDef& d : model_.sockets) d.seed = opts_.seed;  // SIMBOB_SEED of a started controller
  if (cameras_) parties.push_back(cameras_.get());          // before the controllers: they read its images
  robot_ = robotParties(model_, cameras_.get());
  for (auto& p : robot_) parties.push_back(p.get());
  parties.insert(parties.end(), extra_.begin(), extra_.end());
  runner_ = std::make_unique<Runner>(model_, opts_, std::move(parties));
  return runner_->running();
}

bool Simulation::step(uint64_t n) { return start() && runner_->step(n); }

bool Simulation::runUntil(double t) {
  if (!start()) return false;
  const std::optional<SimTime> at = toSimTime(t);
  return runner_->runUntil(at ? std::max<SimTime>(*at, 0) : kNever);
}

const RunResult& Simulation::runToEnd() {
  if (start()) runner_->runUntil(runner_->end());
  return finish();
}

const RunResult& Simulation::finish() {
  start();
  final_ = runner_->complete();
  if (sampler_) final_.samples = sampler_->samples();
  return final_;
}

bool Simulation::reset(uint32_t seed) {
  runner_.reset();  // the old world goes before the new one is built
  robot_.clear();
  opts_.seed = seed;
  writer_ = nullptr;
  on_sample_ = nullptr;
  sampling_ = false;
  return start();
}

const RunResult& Simulation::result() const {
  if (!runner_) return final_;  // not started: nothing has happened yet
  return runner_->result();
}

bool Simulation::running() const { return !runner_ || runner_->running(); }

double Simulation::time() const { return toSeconds(now()); }
SimTime Simulation::now() const { return runner_ ? runner_->clock().now() : 0; }
uint64_t Simulation::steps() const { return runner_ ? runner_->clock().steps() : 0; }
double Simulation::stepSize() const {
  const double dt = resolvedStep(opts_.dt, model_.settings.max_time_step);
  return toSeconds(std::max<SimTime>(toSimTime(dt).value_or(1), 1));
}

World& Simulation::world() {
  start();
  return *runner_->world();
}

const World& Simulation::world() const { return const_cast<Simulation*>(this)->world(); }

namespace {
template <typename T>
int indexOf(const std::vector<T>& defs, const std::string& key) {
  for (size_t i = 0; i < defs.size(); ++i)
    if (defs[i].key == key) return static_cast<int>(i);
  return -1;
}
}  // namespace

int Simulation::body(const std::string& key) const { return indexOf(model_.bodies, key); }
int Simulation::joint(const std::string& key) const { return indexOf(model_.joints, key); }
int Simulation::actuator(const std::string& key) const { return indexOf(model_.actuators, key); }
int Simulation::sensor(const std::string& key) const { return indexOf(model_.sensors, key); }

Error Simulation::setCommand(int actuator, double value) {
  if (actuator < 0 || static_cast<size_t>(actuator) >= model_.actuators.size())
    return {
        ErrorKind::Usage,
        {},
        "no actuator " + std::to_string(actuator) + " (the scene has " + std::to_string(model_.actuators.size()) + ")"};
  if (!std::isfinite(value))
    return {ErrorKind::Usage, model_.actuators[static_cast<size_t>(actuator)].loc,
            "actuator '" + model_.actuators[static_cast<size_t>(actuator)].key + "': the command is not finite"};
  world().setCommand(actuator, value);
  return {};
}

}  // namespace simbob
