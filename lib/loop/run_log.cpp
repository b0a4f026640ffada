// The run log party: joint states, sensor readings and actuator commands at the trajectory's
// sample times, as rows `time,component,quantity,value`.
#include "simbob/tool/csv.h"
#include "loop/run_log.h"

#include <string_view>

#include "simbob/physics.h"
#include "simbob/values.h"

namespace simbob {

namespace {

constexpr size_t kFlushBytes = size_t{1} << 20;

}  // namespace

bool parseRunLogWhat(const std::string& list, RunLogWhat* what, std::string* problem) {
  *what = RunLogWhat{};
  size_t start = 0;
  for (;;) {
    const size_t comma = list.find(',', start);
    const std::string word = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (word == "joints") {
      what->joints = true;
    } else if (word == "sensors") {
      what->sensors = true;
    } else if (word == "commands") {
      what->commands = true;
    } else {
      *problem = "--log: unknown word '" + word + "' (give a comma list of joints, sensors, commands)";
      return false;
    }
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
}

RunLogParty::RunLogParty(const Model& model, RunLogWhat what, SimTime interval, SimTime min_step, OutputFile* out)
    : what_(what),
      timing_(0, interval, min_step, nullptr,
              [this](double t, const double*) {
                pending_ = true;
                pending_t_ = t;
              }),
      out_(out) {
  for (size_t j = 0; j < model.joints.size(); ++j)
    if (model.joints[j].kind == JointKind::Hinge || model.joints[j].kind == JointKind::Slider) {
      joints_.push_back(static_cast<int>(j));
      joint_keys_.push_back(csvField(model.joints[j].key));
    }
  for (const SensorDef& s : model.sensors) {
    sensor_keys_.push_back(csvField(s.key));
    sensor_quantities_.push_back(sensorQuantities(s));
  }
  for (const ActuatorDef& a : model.actuators) actuator_keys_.push_back(csvField(a.key));
  buf_ = std::string(kRunLogHeader) + "\n";
  name = "the run log";
}

RunLogParty::~RunLogParty() { flush(); }

SimTime RunLogParty::first() { return timing_.first(); }

SimTime RunLogParty::onGrant(SimTime now, World& world) {
  const SimTime next = timing_.onGrant(now, world);
  record(toSeconds(now), world);
  return next;
}

void RunLogParty::finish(SimTime end, World& world) {
  pending_ = false;
  timing_.finish(end, world);  // samples only if the last sample was not at `end`
  if (pending_) record(pending_t_, world);
  flush();
}

const Error* RunLogParty::failure() const { return error_.message.empty() ? nullptr : &error_; }

void RunLogParty::record(double t, const World& world) {
  std::string time;
  appendNumber(time, t);
  auto row = [&](const std::string& key, std::string_view quantity, double value) {
    buf_ += time;
    buf_ += ',';
    buf_ += key;
    buf_ += ',';
    buf_ += quantity;
    buf_ += ',';
    appendNumber(buf_, value);
    buf_ += '\n';
  };
  if (what_.joints)
    for (size_t k = 0; k < joints_.size(); ++k) {
      const JointState s = world.joint(joints_[k]);
      row(joint_keys_[k], "pos", s.position);
      row(joint_keys_[k], "vel", s.velocity);
    }
  if (what_.sensors)
    for (size_t k = 0; k < sensor_keys_.size(); ++k) {
      const std::vector<double>& reading = world.sensorReading(static_cast<int>(k));
      for (size_t q = 0; q < reading.size() && q < sensor_quantities_[k].size(); ++q)
        row(sensor_keys_[k], sensor_quantities_[k][q], reading[q]);
    }
  if (what_.commands)
    for (size_t k = 0; k < actuator_keys_.size(); ++k)
      row(actuator_keys_[k], "command", world.command(static_cast<int>(k)));
  if (buf_.size() >= kFlushBytes) flush();
}

bool RunLogParty::flush() {
  if (!buf_.empty()) {
    const bool ok = out_->write(buf_);
    buf_.clear();
    if (!ok && error_.message.empty()) error_ = {ErrorKind::IoError, {out_->path(), 0}, "writing the run log failed"};
  }
  return error_.message.empty();
}

}  // namespace simbob
