// End metrics of a sweep case, from its trajectory.
#include <algorithm>

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
