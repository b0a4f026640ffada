#include "simbob/tool/comparison.h"

#include <algorithm>

#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include "simbob/error.h"
#include "simbob/values.h"

namespace simbob {

namespace {

/// Times print exactly (shortest round-trip) so they can be found in the CSV files.
std::string fmtTime(double t) {
  if (std::isnan(t)) return "nan";
  return formatNumber(t);
}

nlohmann::json optTime(const std::optional<double>& t) { return t ? nlohmann::json(*t) : nlohmann::json(nullptr); }

const char* statusOf(const BodyDiff& d) {
  if (d.exceeded() && d.missingRows()) return "exceeded, missing rows";
  if (d.exceeded()) return "exceeded";
  if (d.missingRows()) return "missing rows";
  return "ok";
}

/// A body name as a report prints it: control bytes and invisible characters escaped, as error
/// messages show input (a name from a CSV must not drive the terminal), never cut.
std::string shown(const std::string& name) { return quoteInput(name, std::numeric_limits<size_t>::max()); }

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out += ", ";
    out += shown(names[i]);
  }
  return out;
}

/// Lays out rows in left-aligned columns separated by two spaces, no trailing blanks.
std::string renderTable(const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> width;
  for (const auto& row : rows) {
    if (width.size() < row.size()) width.resize(row.size(), 0);
    for (size_t c = 0; c < row.size(); ++c)
      if (row[c].size() > width[c]) width[c] = row[c].size();
  }
  std::string out;
  for (const auto& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      if (c) line.append(2, ' ');
      line += row[c];
      if (c + 1 < row.size()) line.append(width[c] - row[c].size(), ' ');
    }
    out += line;
    out += '\n';
  }
  return out;
}

void noteTime(TimeMismatch* m, double t) {
  if (m->count++ == 0) m->first_time = t;
}

}  // namespace

double positionError(const double* p1, const double* p2) {
  const double dx = p1[0] - p2[0];
  const double dy = p1[1] - p2[1];
  const double dz = p1[2] - p2[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double rotationError(const double* q1, const double* q2) {
  // Scale each quaternion by its largest component first: the angle does not depend on the
  // scale, and products of components near 1e154 would overflow.
  auto largest = [](const double* q) {
    double m = std::max({std::fabs(q[0]), std::fabs(q[1]), std::fabs(q[2]), std::fabs(q[3])});
    return m > 0 && std::isfinite(m) ? m : 1.0;
  };
  const double s1 = largest(q1), s2 = largest(q2);
  const double w1 = q1[0] / s1, x1 = q1[1] / s1, y1 = q1[2] / s1, z1 = q1[3] / s1;
  const double w2 = q2[0] / s2, x2 = q2[1] / s2, y2 = q2[2] / s2, z2 = q2[3] / s2;
  // r = conj(q1) * q2: the rotation taking q1 to q2.
  const double rw = w1 * w2 + x1 * x2 + y1 * y2 + z1 * z2;
  const double rx = w1 * x2 - w2 * x1 - (y1 * z2 - z1 * y2);
  const double ry = w1 * y2 - w2 * y1 - (z1 * x2 - x1 * z2);
  const double rz = w1 * z2 - w2 * z1 - (x1 * y2 - y1 * x2);
  const double vn = std::sqrt(rx * rx + ry * ry + rz * rz);
  const double wn = std::fabs(rw);
  if (vn == 0 && wn == 0) {
    // A zero quaternion is no rotation: equal only to another zero quaternion.
    const bool z1zero = w1 == 0 && x1 == 0 && y1 == 0 && z1 == 0;
    const bool z2zero = w2 == 0 && x2 == 0 && y2 == 0 && z2 == 0;
    return z1zero && z2zero ? 0.0 : std::nan("");
  }
  // |rw| makes q and -q equal; atan2 keeps full precision near 0 where acos would not.
  return 2.0 * std::atan2(vn, wn);
}

bool CompareResult::structuralMismatch() const {
  if (!only_actual.empty() || !only_golden.empty()) return true;
  if (times_only_actual.count > 0 || times_only_golden.count > 0) return true;
  for (const BodyDiff& d : bodies)
    if (d.missingRows()) return true;
  return false;
}

CompareResult compareTrajectories(const Trajectory& actual, const Trajectory& golden, const CompareOptions& options) {
  CompareResult r;
  r.options = options;
  r.actual_samples = actual.times.size();
  r.golden_samples = golden.times.size();

  // Bodies: shared ones in golden order, each with its index in both trajectories.
  std::unordered_map<std::string, size_t> actual_index;
  for (size_t i = 0; i < actual.bodies.size(); ++i) actual_index.emplace(actual.bodies[i], i);
  std::unordered_map<std::string, size_t> golden_index;
  std::vector<std::pair<size_t, size_t>> shared;  // (actual body, golden body)
  for (size_t g = 0; g < golden.bodies.size(); ++g) {
    golden_index.emplace(golden.bodies[g], g);
    auto it = actual_index.find(golden.bodies[g]);
    if (it == actual_index.end()) {
      r.only_golden.push_back(golden.bodies[g]);
      continue;
    }
    shared.emplace_back(it->second, g);
    BodyDiff d;
    d.body = golden.bodies[g];
    r.bodies.push_back(std::move(d));
  }
  for (const std::string& key : actual.bodies)
    if (golden_index.find(key) == golden_index.end()) r.only_actual.push_back(key);

  // Samples: merge the two increasing time lists, matching times within time_eps.
  size_t i = 0, j = 0;
  const size_t na = actual.times.size(), ng = golden.times.size();
  while (i < na || j < ng) {
    if (i < na && j < ng && std::fabs(actual.times[i] - golden.times[j]) <= options.time_eps) {
      const double t = golden.times[j];
      ++r.shared_samples;
      for (size_t k = 0; k < shared.size(); ++k) {
        BodyDiff& d = r.bodies[k];
        const double* pa = actual.pose(i, shared[k].first);
        const double* pg = golden.pose(j, shared[k].second);
        if (!pa || !pg) {
          if (pa || pg) {
            ++(pa ? d.missing_in_golden : d.missing_in_actual);
            if (!d.first_missing_time) d.first_missing_time = t;
          }
          continue;
        }
        const double pe = positionError(pa, pg);
        const double re = rotationError(pa + 3, pg + 3);
        // Strictly greater keeps the first time of the maximum; NaN always wins.
        if (d.compared == 0 || pe > d.max_pos_err || (std::isnan(pe) && !std::isnan(d.max_pos_err))) {
          d.max_pos_err = pe;
          d.max_pos_time = t;
        }
        if (d.compared == 0 || re > d.max_rot_err || (std::isnan(re) && !std::isnan(d.max_rot_err))) {
          d.max_rot_err = re;
          d.max_rot_time = t;
        }
        ++d.compared;
        // Written as !(err <= tol) so a NaN error counts as exceeding.
        const bool pos_ex = !(pe <= options.tol_pos);
        const bool rot_ex = !(re <= options.tol_rot);
        if ((pos_ex || rot_ex) && !d.first_exceed_time) {
          d.first_exceed_time = t;
          d.first_exceed_pos_err = pe;
          d.first_exceed_rot_err = re;
          // Samples are visited in time order, so the first one found overall is the earliest.
          if (!r.first_divergence) r.first_divergence = Divergence{t, d.body, pe, re, pos_ex, rot_ex};
        }
      }
      ++i;
      ++j;
    } else if (j == ng || (i < na && actual.times[i] < golden.times[j])) {
      noteTime(&r.times_only_actual, actual.times[i]);
      ++i;
    } else {
      noteTime(&r.times_only_golden, golden.times[j]);
      ++j;
    }
  }

  bool within = true;
  for (const BodyDiff& d : r.bodies)
    if (d.exceeded()) within = false;
  r.pass = within && !r.structuralMismatch();
  return r;
}

std::string CompareResult::text() const {
  std::vector<std::vector<std::string>> rows;
  rows.push_back({"body", "max pos err (m)", "max rot err (rad)", "first exceed (s)", "status"});
  for (const BodyDiff& d : bodies) {
    const bool any = d.compared > 0;
    rows.push_back({shown(d.body), any ? formatApprox(d.max_pos_err) : "-", any ? formatApprox(d.max_rot_err) : "-",
                    d.first_exceed_time ? fmtTime(*d.first_exceed_time) : "-", statusOf(d)});
  }
  for (const std::string& b : only_actual) rows.push_back({shown(b), "-", "-", "-", "only in actual"});
  for (const std::string& b : only_golden) rows.push_back({shown(b), "-", "-", "-", "only in golden"});
  std::string out = renderTable(rows);

  out += "\ntolerances: pos " + formatApprox(options.tol_pos) + " m, rot " + formatApprox(options.tol_rot) + " rad\n";
  out += "samples: " + std::to_string(actual_samples) + " actual, " + std::to_string(golden_samples) + " golden, " +
         std::to_string(shared_samples) + " shared\n";
  auto timesLine = [&out](const char* which, const TimeMismatch& m) {
    if (m.count == 0) return;
    out += std::string("sample times only in ") + which + ": " + std::to_string(m.count) +
           " (first at t=" + fmtTime(*m.first_time) + ")\n";
  };
  timesLine("actual", times_only_actual);
  timesLine("golden", times_only_golden);
  if (!only_actual.empty()) out += "bodies only in actual: " + joinNames(only_actual) + "\n";
  if (!only_golden.empty()) out += "bodies only in golden: " + joinNames(only_golden) + "\n";
  for (const BodyDiff& d : bodies) {
    if (!d.missingRows()) continue;
    out += "missing rows for " + shown(d.body) + ": " + std::to_string(d.missing_in_actual) + " in actual, " +
           std::to_string(d.missing_in_golden) + " in golden (first at t=" + fmtTime(*d.first_missing_time) + ")\n";
  }
  if (first_divergence) {
    const Divergence& v = *first_divergence;
    out += "first divergence: t=" + fmtTime(v.time) + " body " + shown(v.body) + ": pos err " +
           formatApprox(v.pos_err) + " m" + (v.pos_exceeded ? " (exceeds)" : "") + ", rot err " +
           formatApprox(v.rot_err) + " rad" + (v.rot_exceeded ? " (exceeds)" : "") + "\n";
  }
  out += pass ? "result: PASS\n" : "result: FAIL\n";
  return out;
}

nlohmann::json CompareResult::json() const {
  using nlohmann::json;
  json j;
  j["pass"] = pass;
  j["structural_mismatch"] = structuralMismatch();
  j["tolerances"] = {{"pos", options.tol_pos}, {"rot", options.tol_rot}, {"time_eps", options.time_eps}};
  auto times = [](const TimeMismatch& m) { return json{{"count", m.count}, {"first_time", optTime(m.first_time)}}; };
  j["samples"] = {{"actual", actual_samples},
                  {"golden", golden_samples},
                  {"shared", shared_samples},
                  {"only_actual", times(times_only_actual)},
                  {"only_golden", times(times_only_golden)}};
  j["bodies_only_actual"] = only_actual;
  j["bodies_only_golden"] = only_golden;
  json list = json::array();
  for (const BodyDiff& d : bodies) {
    const bool any = d.compared > 0;
    list.push_back(json{{"body", d.body},
                        {"compared", d.compared},
                        {"max_pos_err", d.max_pos_err},
                        {"max_pos_time", any ? json(d.max_pos_time) : json(nullptr)},
                        {"max_rot_err", d.max_rot_err},
                        {"max_rot_time", any ? json(d.max_rot_time) : json(nullptr)},
                        {"first_exceed_time", optTime(d.first_exceed_time)},
                        {"first_exceed_pos_err", d.exceeded() ? json(d.first_exceed_pos_err) : json(nullptr)},
                        {"first_exceed_rot_err", d.exceeded() ? json(d.first_exceed_rot_err) : json(nullptr)},
                        {"missing_in_actual", d.missing_in_actual},
                        {"missing_in_golden", d.missing_in_golden},
                        {"first_missing_time", optTime(d.first_missing_time)},
                        {"status", statusOf(d)},
                        {"pass", d.pass()}});
  }
  j["bodies"] = std::move(list);
  if (first_divergence) {
    const Divergence& v = *first_divergence;
    j["first_divergence"] = {{"time", v.time},
                             {"body", v.body},
                             {"pos_err", v.pos_err},
                             {"rot_err", v.rot_err},
                             {"pos_exceeded", v.pos_exceeded},
                             {"rot_exceeded", v.rot_exceeded}};
  } else {
    j["first_divergence"] = nullptr;
  }
  return j;
}

}  // namespace simbob
