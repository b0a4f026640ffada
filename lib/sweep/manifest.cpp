// Sweep manifests: one case per line as compact JSON (docs/sweeps.md).
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "simbob/tool/sweep_plan.h"
#include "simbob/values.h"

namespace simbob {

namespace {

using ojson = nlohmann::ordered_json;

// Throws std::runtime_error (turned into "MANIFEST:LINE: ...") when a field is missing or wrong.
const nlohmann::json& field(const nlohmann::json& j, const char* key) {
  if (!j.contains(key)) throw std::runtime_error(std::string("'") + key + "' is missing");
  return j[key];
}

// A whole number from lo to hi (a JSON integer, or a number with no fraction such as 1e3).
double wholeNumber(const nlohmann::json& j, const char* key, double lo, double hi) {
  const nlohmann::json& v = field(j, key);
  const double d = v.is_number() ? v.get<double>() : NAN;
  if (!v.is_number() || !(d >= lo && d <= hi) || std::floor(d) != d ||
      (v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() < 0 && lo >= 0))
    throw std::runtime_error(std::string("'") + key + "' must be a whole number from " + formatNumber(lo) + " to " +
                             formatNumber(hi) + ", got " + v.dump());
  return d;
}

// A time in s from 1e-9 to 1e9, as `simbob sweep plan` writes it.
double seconds(const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = field(j, key);
  if (!v.is_number() || !(v.get<double>() >= 1e-9 && v.get<double>() <= 1e9))
    throw std::runtime_error(std::string("'") + key + "' must be a number of seconds from 1e-9 to 1e9, got " +
                             v.dump());
  return v.get<double>();
}

}  // namespace

std::string manifestLine(const SweepCase& c) {
  ojson j;
  j["case"] = c.index;
  j["scene"] = c.scene;
  j["duration"] = c.duration;
  if (c.dt > 0) j["dt"] = c.dt;
  j["sample_interval"] = c.sample_interval;
  j["seed"] = c.seed;
  ojson vary = ojson::object();
  for (const auto& [k, v] : c.vary) vary[k] = v;
  j["vary"] = vary;
  j["set"] = c.set;
  ojson metrics = ojson::array();
  for (const SweepMetric& m : c.metrics)
    metrics.push_back({{"name", m.name}, {"body", m.body}, {"value", m.value}, {"stat", m.stat}});
  j["metrics"] = metrics;
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool parseManifest(const std::string& text, const std::string& path, std::vector<SweepCase>* cases, Error* err) {
  cases->clear();
  size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) nl = text.size();
    const std::string line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      const nlohmann::json j = nlohmann::json::parse(line);
      SweepCase c;
      if (!j.is_object()) throw std::runtime_error("a case is a JSON object");
      c.index = static_cast<int>(wholeNumber(j, "case", 0, 999999999));
      if (c.index != static_cast<int>(cases->size()))
        throw std::runtime_error("case " + std::to_string(c.index) + " where case " + std::to_string(cases->size()) +
                                 " was expected (cases are numbered from 0, one per line)");
      c.scene = field(j, "scene").get<std::string>();
      if (c.scene.find('\0') != std::string::npos)
        throw std::runtime_error("'scene' holds a NUL character (\\u0000), which no file name can hold");
      c.duration = seconds(j, "duration");
      if (j.contains("dt")) c.dt = seconds(j, "dt");
      c.sample_interval = seconds(j, "sample_interval");
      c.seed = static_cast<uint32_t>(wholeNumber(j, "seed", 0, 4294967295.0));
      for (const auto& [k, v] : field(j, "vary").items()) c.vary.emplace_back(k, v.get<std::string>());
      c.set = field(j, "set").get<std::vector<std::string>>();
      for (const std::string& set : c.set)
        if (set.find('\0') != std::string::npos)
          throw std::runtime_error("a 'set' entry holds a NUL character (\\u0000), which no command line can pass");
      for (const auto& m : field(j, "metrics"))
        c.metrics.push_back({field(m, "name").get<std::string>(), field(m, "body").get<std::string>(),
                             field(m, "value").get<std::string>(), field(m, "stat").get<std::string>()});
      cases->push_back(std::move(c));
    } catch (const std::exception& e) {
      std::string what = e.what();
      if (size_t b = what.find("] "); what.rfind("[json.exception", 0) == 0 && b != std::string::npos)
        what = what.substr(b + 2);
      *err = {ErrorKind::InvalidInput, {path, line_no}, "not a sweep case: " + what};
      return false;
    }
  }
  if (cases->empty()) {
    *err = {ErrorKind::InvalidInput, {path, 0}, "no cases (a manifest has one JSON case per line)"};
    return false;
  }
  return true;
}

std::string caseDirName(int index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "case-%04d", index);
  return buf;
}

std::string arrayList(const std::vector<int>& indices) {
  std::string s;
  for (size_t i = 0; i < indices.size(); ++i) s += (i ? "," : "") + std::to_string(indices[i]);
  return s;
}

}  // namespace simbob
