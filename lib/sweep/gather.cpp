// End metrics of a sweep case, from its trajectory.
#include <algorithm>

#include "simbob/csv.h"
#include "simbob/sweep.h"
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

}  // namespace simbob
