// End metrics of a sweep case, from its trajectory.
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "simbob/tool/csv.h"
#include "simbob/tool/files.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob {

bool computeMetrics(const Trajectory& t, const std::vector<SweepMetric>& metrics, std::vector<double>* values,
                    std::string* error) {
  values->clear();
  for (const SweepMetric& m : metrics) {
    auto it = std::find(t.bodies.begin(), t.bodies.end(), m.body);
    if (it == t.bodies.end()) {
      std::string near = didYouMean(m.body, t.bodies);
      *error = "metric '" + m.name + "': no body '" + quoteInput(m.body) + "' in the trajectory" +
               (near.empty() ? "" : " (did you mean '" + near + "'?)");
      return false;
    }
    const size_t b = static_cast<size_t>(it - t.bodies.begin());
    const size_t k = m.value == "x" ? 0 : m.value == "y" ? 1 : 2;
    bool any = false;
    double first = 0, last = 0, lo = 0, hi = 0;
    for (size_t s = 0; s < t.sampleCount(); ++s) {
      const double* p = t.pose(s, b);
      if (!p) continue;
      const double v = p[k];
      if (!any) first = lo = hi = v;
      any = true;
      last = v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (!any) {
      *error = "metric '" + m.name + "': body '" + quoteInput(m.body) + "' has no samples";
      return false;
    }
    if (m.stat == "final") values->push_back(last);
    if (m.stat == "initial") values->push_back(first);
    if (m.stat == "max") values->push_back(hi);
    if (m.stat == "min") values->push_back(lo);
    if (m.stat == "delta") values->push_back(last - first);
  }
  return true;
}

}  // namespace simbob

namespace simbob {

bool sweepTableSeries(const std::string& text, const std::string& path, const std::string& x_col,
                      const std::string& y_col, Trajectory* out, Error* err) {
  std::vector<int> lines;
  std::vector<std::vector<std::string>> rows;
  CsvReader csv(text, path);
  Error bad;
  while (csv.next(&bad)) {
    rows.emplace_back(csv.fields().begin(), csv.fields().end());
    lines.push_back(csv.line());
  }
  if (!bad.message.empty()) {
    *err = bad;
    return false;
  }
  if (rows.empty()) {
    *err = {ErrorKind::InvalidInput, {path, 0}, "empty table"};
    return false;
  }
  const std::vector<std::string>& head = rows[0];
  auto column = [&](const std::string& name, size_t* index) {
    auto it = std::find(head.begin(), head.end(), name);
    if (it != head.end()) {
      *index = static_cast<size_t>(it - head.begin());
      return true;
    }
    const std::string near = didYouMean(name, head);
    *err = {ErrorKind::InvalidInput,
            {path, 1},
            "no column '" + quoteInput(name) + "'" + (near.empty() ? "" : " (did you mean '" + near + "'?)")};
    return false;
  };
  size_t xi = 0, yi = 0, si = 0;
  if (!column(x_col, &xi) || !column(y_col, &yi) || !column("status", &si)) return false;
  std::vector<std::pair<double, double>> points;
  for (size_t r = 1; r < rows.size(); ++r) {
    const std::vector<std::string>& row = rows[r];
    if (row.size() != head.size()) {
      *err = {ErrorKind::InvalidInput,
              {path, lines[r]},
              std::to_string(row.size()) + " fields, the header has " + std::to_string(head.size())};
      return false;
    }
    if (row[si] != "ok") continue;  // failed and missing cases have no metrics
    auto x = parseNumber(row[xi]);
    auto y = parseNumber(row[yi]);
    if (!x || !y) {
      *err = {ErrorKind::InvalidInput, {path, lines[r]}, "'" + quoteInput(row[x ? yi : xi]) + "' is not a number"};
      return false;
    }
    points.emplace_back(*x, *y);
  }
  std::sort(points.begin(), points.end());
  for (size_t i = 1; i < points.size(); ++i)
    if (points[i].first == points[i - 1].first) {
      *err = {ErrorKind::InvalidInput,
              {path, 0},
              "several cases have " + x_col + " = " + formatNumber(points[i].first) +
                  "; plot a table where it is the only varied parameter"};
      return false;
    }
  *out = Trajectory{};
  out->addBody(y_col);
  for (size_t i = 0; i < points.size(); ++i) {
    out->times.push_back(points[i].first);
    const double pose[kPoseSize] = {points[i].second, 0, 0, 1, 0, 0, 0};
    out->setPose(i, 0, pose);
  }
  out->finalize();
  return true;
}

namespace {

// One case's row values from its case.json: status, wall time, error and metric texts.
void readCase(const std::string& dir, const SweepCase& c, GatheredCase* g, std::string* wall,
              std::vector<std::string>* values) {
  values->assign(c.metrics.size(), "");
  std::string jt;
  if (!readFile(dir + "/case.json", 1 << 20, &jt, nullptr, true)) return;
  // A field of the wrong type makes the case failed, never the gather.
  try {
    const nlohmann::json j = nlohmann::json::parse(jt);
    if (!j.is_object()) throw std::runtime_error("not a JSON object");
    g->status = j.value("status", "failed");
    *wall = formatNumber(j.value("wall_seconds", 0.0));
    g->error = j.value("error", "");
    if (g->status != "ok") return;
    for (size_t i = 0; i < c.metrics.size(); ++i) {
      const std::string& name = c.metrics[i].name;
      if (!j.contains("metrics") || !j["metrics"].is_object() || !j["metrics"].contains(name)) continue;
      const nlohmann::json& v = j["metrics"][name];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw std::runtime_error("metric '" + name + "' is " + v.dump() + ", not a number");
      (*values)[i] = formatNumber(v.get<double>());
    }
  } catch (const std::exception& e) {
    g->status = "failed";
    std::string what = e.what();  // "[json.exception.type_error.302] type must be ...": the part after "] "
    if (size_t b = what.find("] "); what.rfind("[json.exception", 0) == 0 && b != std::string::npos)
      what = what.substr(b + 2);
    g->error = "unreadable case.json: " + what;
    values->assign(c.metrics.size(), "");
  }
}

}  // namespace

GatheredTable gatherSweep(const std::string& out_dir, const std::vector<SweepCase>& cases) {
  GatheredTable t;
  if (cases.empty()) return t;
  const SweepCase& first = cases.front();
  t.csv = "case";
  for (const auto& [k, v] : first.vary) t.csv += "," + csvField(k);
  t.csv += ",seed,status,wall_seconds";
  for (const SweepMetric& m : first.metrics) t.csv += "," + csvField(m.name);
  t.csv += "\n";
  for (const SweepCase& c : cases) {
    GatheredCase g;
    g.index = c.index;
    std::string wall;
    std::vector<std::string> values;
    readCase(out_dir + "/" + caseDirName(c.index), c, &g, &wall, &values);
    t.csv += std::to_string(c.index);
    for (const auto& [k, v] : c.vary) t.csv += "," + csvField(v);
    t.csv += "," + std::to_string(c.seed) + "," + csvField(g.status) + "," + csvField(wall);
    for (const std::string& v : values) t.csv += "," + v;
    t.csv += "\n";
    t.cases.push_back(std::move(g));
  }
  return t;
}

nlohmann::ordered_json sweepCaseRecord(const SweepCase& c, const std::string& dir, int exit_code,
                                       const std::string& error, double wall) {
  nlohmann::ordered_json j;
  j["case"] = c.index;
  j["status"] = exit_code == 0 ? "ok" : exit_code == 1 ? "diverged" : "failed";
  j["exit_code"] = exit_code;
  if (!error.empty()) j["error"] = error;
  j["wall_seconds"] = wall;
  j["seed"] = c.seed;
  nlohmann::ordered_json vary = nlohmann::ordered_json::object();
  for (const auto& [k, v] : c.vary) vary[k] = v;
  j["vary"] = vary;
  j["set"] = c.set;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  if (exit_code == 0) {
    Trajectory t;
    Error terr;
    std::vector<double> values;
    std::string merr;
    if (!readTrajectory(dir + "/trajectory.csv", &t, &terr)) {
      merr = terr.str();
    } else if (computeMetrics(t, c.metrics, &values, &merr)) {
      for (size_t i = 0; i < values.size(); ++i) metrics[c.metrics[i].name] = values[i];
    }
    if (!merr.empty()) {
      j["status"] = "failed";
      j["error"] = merr;
      j["exit_code"] = 65;  // EX_DATAERR: the trajectory does not hold what a metric needs
    }
  }
  j["metrics"] = metrics;
  return j;
}

}  // namespace simbob
