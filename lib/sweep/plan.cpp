// Sweep descriptions (JSON) expanded into numbered cases: lists, ranges, zip groups, grids.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "simbob/options.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/values.h"

namespace simbob {

namespace {

using nlohmann::json;

// A problem with what the JSON says (not its syntax): "vary[1].range: 'step' must be > 0".
struct PlanError {
  std::string message;
};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw PlanError{(where.empty() ? "" : where + ": ") + what};
}

bool parseJson(const std::string& text, const std::string& path, json* out, Error* err) {
  try {
    *out = json::parse(text);
    return true;
  } catch (const json::parse_error& e) {
    int line = 1;
    for (size_t i = 0; i < e.byte && i < text.size(); ++i) line += text[i] == '\n' ? 1 : 0;
    std::string what = e.what();
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..."
    if (size_t colon = what.find(": ", what.find("parse error")); colon != std::string::npos)
      what = what.substr(colon + 2);
    *err = {ErrorKind::InvalidInput, {path, line}, "not valid JSON: " + what};
    return false;
  }
}

void onlyKeys(const json& j, const std::string& where, std::initializer_list<const char*> keys) {
  for (const auto& [k, v] : j.items()) {
    std::vector<std::string> known(keys.begin(), keys.end());
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      std::string near = didYouMean(k, known);
      fail(where, "unknown field '" + quoteInput(k) + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
  }
}

double number(const json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) fail(where, std::string("'") + key + "' is required");
  if (!j[key].is_number()) fail(where, std::string("'") + key + "' must be a number");
  double v = j[key].get<double>();
  if (!std::isfinite(v)) fail(where, std::string("'") + key + "' must be finite");
  return v;
}

// Range values are start + i * step, rounded to 12 significant digits so that 0.1 + 2 * 0.1
// reads 0.3 (the sum is 0.30000000000000004 in binary).
std::string rangeValue(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  auto parsed = parseNumber(buf);
  return formatNumber(parsed ? *parsed : v);
}

std::string valueText(const json& v, const std::string& where) {
  if (v.is_number_integer()) return std::to_string(v.get<int64_t>());
  if (v.is_number()) return formatNumber(v.get<double>());
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "True" : "False";
  fail(where, "values must be numbers, strings or booleans");
}

constexpr size_t kMaxCases = 1000000;

// The values of one varied parameter: "values" or "range". With `count`, only checks the entry
// and sets *count to the number of values, making none (the grid's size is known before any
// dimension is spent).
std::vector<std::string> values(const json& e, const std::string& where, size_t* count = nullptr) {
  if (e.contains("values") == e.contains("range")) fail(where, "give either 'values' (a list) or 'range'");
  std::vector<std::string> out;
  if (e.contains("values")) {
    if (!e["values"].is_array() || e["values"].empty()) fail(where, "'values' must be a non-empty list");
    if (count) {
      *count = e["values"].size();
      return out;
    }
    for (size_t i = 0; i < e["values"].size(); ++i)
      out.push_back(valueText(e["values"][i], where + ".values[" + std::to_string(i) + "]"));
    return out;
  }
  const json& r = e["range"];
  const std::string rw = where + ".range";
  if (!r.is_object()) fail(rw, "must be an object {\"start\", \"stop\", \"step\" or \"count\"}");
  onlyKeys(r, rw, {"start", "stop", "step", "count"});
  const double start = number(r, "start", rw), stop = number(r, "stop", rw);
  if (r.contains("step") == r.contains("count")) fail(rw, "give either 'step' or 'count'");
  if (r.contains("count")) {
    if (!r["count"].is_number_integer() || r["count"].get<int64_t>() < 1 ||
        r["count"].get<int64_t>() > static_cast<int64_t>(kMaxCases))
      fail(rw, "'count' must be an integer from 1 to 1000000");
    const int64_t n = r["count"].get<int64_t>();
    if (count) {
      *count = static_cast<size_t>(n);
      return out;
    }
    // Both ends included: start, start + (stop - start) / (n - 1), ..., stop.
    for (int64_t i = 0; i < n; ++i)
      out.push_back(rangeValue(n == 1 ? start : start + (stop - start) * static_cast<double>(i) / (n - 1)));
    return out;
  }
  const double step = number(r, "step", rw);
  if (!(step > 0)) fail(rw, "'step' must be > 0");
  if (stop < start) fail(rw, "'stop' must not be below 'start'");
  // Stop included when it lies on the grid (within a billionth of a step).
  const double n = std::floor((stop - start) / step + 1e-9) + 1;
  if (n > static_cast<double>(kMaxCases)) fail(rw, "more than 1000000 values");
  if (count) {
    *count = static_cast<size_t>(n);
    return out;
  }
  for (int64_t i = 0; i < static_cast<int64_t>(n); ++i)
    out.push_back(rangeValue(start + static_cast<double>(i) * step));
  return out;
}

// One dimension of the grid: one parameter, or a zip of several that change together.
struct Dimension {
  std::vector<std::string> params;
  std::vector<std::vector<std::string>> rows;  // rows[i][p]
};

std::string paramName(const json& e, const std::string& where) {
  if (!e.contains("param") || !e["param"].is_string() || e["param"].get<std::string>().empty())
    fail(where, "'param' (KEY.PARAM, or \"seed\") is required");
  return e["param"].get<std::string>();
}

Dimension dimension(const json& e, const std::string& where) {
  if (!e.is_object()) fail(where, "must be an object");
  Dimension d;
  if (e.contains("zip")) {
    onlyKeys(e, where, {"zip"});
    if (!e["zip"].is_array() || e["zip"].size() < 2) fail(where, "'zip' must list two or more parameters");
    for (size_t k = 0; k < e["zip"].size(); ++k) {
      const std::string w = where + ".zip[" + std::to_string(k) + "]";
      const json& z = e["zip"][k];
      if (!z.is_object()) fail(w, "must be an object");
      onlyKeys(z, w, {"param", "values", "range"});
      d.params.push_back(paramName(z, w));
      std::vector<std::string> vs = values(z, w);
      if (k == 0) d.rows.resize(vs.size());
      if (vs.size() != d.rows.size())
        fail(w, "has " + std::to_string(vs.size()) + " values, zip[0] has " + std::to_string(d.rows.size()) +
                    " (zipped parameters change together, so they need as many values)");
      for (size_t i = 0; i < vs.size(); ++i) d.rows[i].push_back(vs[i]);
    }
    return d;
  }
  onlyKeys(e, where, {"param", "values", "range"});
  d.params.push_back(paramName(e, where));
  for (std::string& v : values(e, where)) d.rows.push_back({std::move(v)});
  return d;
}

uint32_t seedValue(const std::string& text, const std::string& where) {
  auto n = parseNumber(text);
  if (!n || *n < 0 || *n > 4294967295.0 || std::floor(*n) != *n)
    fail(where, "a seed must be an integer from 0 to 4294967295, got '" + quoteInput(text) + "'");
  return static_cast<uint32_t>(*n);
}

void checkOverrideKey(const std::string& param, const std::string& where) {
  const size_t dot = param.rfind('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == param.size() || param.find('=') != std::string::npos)
    fail(where, "'param' must be KEY.PARAM (a component key, '.', a parameter name) or \"seed\", got '" +
                    quoteInput(param) + "'");
}

}  // namespace

bool sweepScene(const std::string& text, const std::string& path, std::string* scene, Error* err) {
  json j;
  if (!parseJson(text, path, &j, err)) return false;
  if (!j.is_object() || !j.contains("scene") || !j["scene"].is_string() || j["scene"].get<std::string>().empty()) {
    *err = {ErrorKind::InvalidInput, {path, 0}, "'scene' (the base scene file) is required"};
    return false;
  }
  *scene = j["scene"].get<std::string>();
  if (scene->find('\0') != std::string::npos) {
    *err = {ErrorKind::InvalidInput, {path, 0}, "'scene' holds a NUL character (\\u0000), which no file name can hold"};
    return false;
  }
  return true;
}

namespace {

/// Metric `w` of a sweep description (w = "metrics[i]"), checked against those before it.
SweepMetric metric(const json& m, const std::string& w, const std::vector<SweepMetric>& before) {
  if (!m.is_object()) fail(w, "must be an object {\"name\", \"body\", \"value\", \"stat\"}");
  onlyKeys(m, w, {"name", "body", "value", "stat"});
  SweepMetric sm;
  for (auto [field, dst] : {std::pair<const char*, std::string*>{"name", &sm.name},
                            {"body", &sm.body},
                            {"value", &sm.value},
                            {"stat", &sm.stat}}) {
    if (m.contains(field) && !m[field].is_string()) fail(w, std::string("'") + field + "' must be a string");
    if (m.contains(field)) *dst = m[field].get<std::string>();
  }
  if (sm.name.empty() || sm.body.empty()) fail(w, "'name' and 'body' are required");
  if (sm.value != "x" && sm.value != "y" && sm.value != "z")
    fail(w, "'value' must be x, y or z, got '" + quoteInput(sm.value) + "'");
  static const std::vector<std::string> kStats = {"final", "initial", "max", "min", "delta"};
  if (std::find(kStats.begin(), kStats.end(), sm.stat) == kStats.end()) {
    std::string near = didYouMean(sm.stat, kStats);
    fail(w, "'stat' must be final, initial, max, min or delta, got '" + quoteInput(sm.stat) + "'" +
                (near.empty() ? "" : " (did you mean '" + near + "'?)"));
  }
  for (const SweepMetric& o : before)
    if (o.name == sm.name) fail(w, "metric name '" + quoteInput(sm.name) + "' given twice");
  return sm;
}

/// The dimensions of `vary`, after counting the cases from the counts alone: each count is at
/// most 1000000 and the product so far too, so no product overflows.
std::vector<Dimension> dimensions(const json& j) {
  std::vector<Dimension> dims;
  if (!j.contains("vary")) return dims;
  if (!j["vary"].is_array()) fail("vary", "must be a list");
  size_t total = 1;
  for (size_t i = 0; i < j["vary"].size(); ++i) {
    const json& e = j["vary"][i];
    std::string w = "vary[" + std::to_string(i) + "]";
    const json* first = &e;
    if (!e.is_object()) continue;  // dimension() says what is wrong
    // Checked in the order dimension() checks them, so the first problem is the one named.
    if (e.contains("zip")) {
      onlyKeys(e, w, {"zip"});
      if (!e["zip"].is_array() || e["zip"].size() < 2 || !e["zip"][0].is_object()) continue;
      first = &e["zip"][0];
      w += ".zip[0]";
    }
    onlyKeys(*first, w, {"param", "values", "range"});
    paramName(*first, w);
    size_t n = 0;
    values(*first, w, &n);
    total *= n;
    if (total > kMaxCases) fail("vary", "more than 1000000 cases");
  }
  for (size_t i = 0; i < j["vary"].size(); ++i)
    dims.push_back(dimension(j["vary"][i], "vary[" + std::to_string(i) + "]"));
  return dims;
}

}  // namespace

bool planSweep(const std::string& text, const std::string& path, const std::string& scene_rel,
               std::vector<SweepCase>* cases, Error* err) {
  json j;
  if (!parseJson(text, path, &j, err)) return false;
  try {
    if (!j.is_object()) fail("", "a sweep description is a JSON object");
    onlyKeys(j, "", {"scene", "duration", "dt", "sample_interval", "seed", "seed_per_case", "set", "vary", "metrics"});
    SweepCase base;
    base.scene = scene_rel;
    base.duration = number(j, "duration", "");
    if (j.contains("dt")) base.dt = number(j, "dt", "");
    if (j.contains("sample_interval")) base.sample_interval = number(j, "sample_interval", "");
    for (const auto& [name, v] : std::initializer_list<std::pair<const char*, double>>{
             {"duration", base.duration}, {"sample_interval", base.sample_interval}})
      if (!clockTimeProblem(name, v).empty()) fail("", std::string("'") + name + "' must be between 1e-9 and 1e9 s");
    if (j.contains("dt") && !clockTimeProblem("dt", base.dt).empty()) fail("", "'dt' must be between 1e-9 and 1e9 s");
    if (j.contains("seed")) {
      if (!j["seed"].is_number_integer()) fail("", "'seed' must be an integer");
      base.seed = seedValue(std::to_string(j["seed"].get<int64_t>()), "seed");
    }
    bool per_case = false;
    if (j.contains("seed_per_case")) {
      if (!j["seed_per_case"].is_boolean()) fail("", "'seed_per_case' must be true or false");
      per_case = j["seed_per_case"].get<bool>();
    }
    if (j.contains("set")) {
      if (!j["set"].is_array()) fail("set", "must be a list of \"KEY.PARAM=VALUE\"");
      for (size_t i = 0; i < j["set"].size(); ++i) {
        const std::string w = "set[" + std::to_string(i) + "]";
        if (!j["set"][i].is_string()) fail(w, "must be a string \"KEY.PARAM=VALUE\"");
        const std::string s = j["set"][i].get<std::string>();
        const size_t eq = s.find('=');
        if (eq == std::string::npos) fail(w, "expected KEY.PARAM=VALUE, got '" + quoteInput(s) + "'");
        checkOverrideKey(s.substr(0, eq), w);
        base.set.push_back(s);
      }
    }
    if (j.contains("metrics")) {
      if (!j["metrics"].is_array()) fail("metrics", "must be a list");
      for (size_t i = 0; i < j["metrics"].size(); ++i)
        base.metrics.push_back(metric(j["metrics"][i], "metrics[" + std::to_string(i) + "]", base.metrics));
    }
    const std::vector<Dimension> dims = dimensions(j);
    std::vector<std::string> names;
    for (size_t d = 0; d < dims.size(); ++d)
      for (const std::string& p : dims[d].params) {
        const std::string w = "vary[" + std::to_string(d) + "]";
        if (std::find(names.begin(), names.end(), p) != names.end())
          fail(w, "parameter '" + quoteInput(p) + "' varied twice");
        if (p != "seed") checkOverrideKey(p, w);
        if (p == "seed" && per_case) fail(w, "\"seed\" is varied and 'seed_per_case' is set; choose one");
        names.push_back(p);
      }
    double total = 1;
    for (const Dimension& d : dims) total *= static_cast<double>(d.rows.size());
    if (total > static_cast<double>(kMaxCases)) fail("vary", "more than 1000000 cases");
    const size_t n = static_cast<size_t>(total);
    cases->clear();
    cases->reserve(n);
    for (size_t i = 0; i < n; ++i) {
      SweepCase c = base;
      c.index = static_cast<int>(i);
      if (per_case) c.seed = base.seed + static_cast<uint32_t>(i);
      // Row-major: the last dimension changes fastest.
      size_t rest = i, stride = n;
      for (const Dimension& d : dims) {
        stride /= d.rows.size();
        const std::vector<std::string>& row = d.rows[rest / stride];
        rest %= stride;
        for (size_t p = 0; p < d.params.size(); ++p) {
          c.vary.emplace_back(d.params[p], row[p]);
          if (d.params[p] == "seed")
            c.seed = seedValue(row[p], "vary");
          else
            c.set.push_back(d.params[p] + "=" + row[p]);
        }
      }
      cases->push_back(std::move(c));
    }
    return true;
  } catch (const PlanError& e) {
    *err = {ErrorKind::InvalidInput, {path, 0}, e.message};
    return false;
  }
}

}  // namespace simbob
