// The parts of CI reports that batch, compare and sweep gather share (ci_report.h).
#include "ci_report.h"

#include <unistd.h>

#include <filesystem>
#include <set>

#include "cli.h"
#include "simbob/physics.h"
#include "simbob/tool/platform.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/values.h"
#include "version.h"

namespace simbob::cli {

std::string versionText() {
  return versionLine() + "\nODE " + odeVersion() + " (" + physicsVersion() + ")\ncompiler " + compilerVersion() + "\n" +
         libcVersion() + "\n";
}

TestSuiteReport ciSuite(const std::string& name) {
  TestSuiteReport s;
  s.name = name;
  s.timestamp = isoTimestamp();
  char host[256] = {};
  s.hostname = ::gethostname(host, sizeof host - 1) == 0 && host[0] ? host : "localhost";
  s.properties = {{"simbob.version", SIMBOB_VERSION}, {"simbob.revision", kGitRevision},
                  {"ode.version", odeVersion()},      {"ode.configuration", physicsVersion()},
                  {"compiler", compilerVersion()},    {"libc", libcVersion()},
                  {"cpu.model", cpuModel()}};
  return s;
}

std::string testClassName(const std::string& path) {
  std::filesystem::path p = std::filesystem::path(path).lexically_normal();
  std::string s = p.replace_extension().generic_string();
  while (s.rfind("./", 0) == 0) s.erase(0, 2);
  while (!s.empty() && s[0] == '/') s.erase(0, 1);
  for (char& c : s)
    if (c == '/') c = '.';
  return s;
}

// The failure's one line: where the run first left the golden one, against the tolerances.
std::string divergenceMessage(const CompareResult& r) {
  if (r.first_divergence) {
    const Divergence& d = *r.first_divergence;
    return "first divergence at t=" + formatNumber(d.time) + " s, body '" + d.body + "': position error " +
           formatApprox(d.pos_err) + " m (tolerance " + formatApprox(r.options.tol_pos) + " m), rotation error " +
           formatApprox(d.rot_err) + " rad (tolerance " + formatApprox(r.options.tol_rot) + " rad)";
  }
  std::string why = "the trajectories differ in bodies, sample times or rows";
  if (!r.only_actual.empty()) return why + ": body '" + r.only_actual[0] + "' only in the run";
  if (!r.only_golden.empty()) return why + ": body '" + r.only_golden[0] + "' only in the golden file";
  if (r.times_only_actual.count)
    return why + ": sample time " + formatNumber(*r.times_only_actual.first_time) + " s only in the run";
  if (r.times_only_golden.count)
    return why + ": sample time " + formatNumber(*r.times_only_golden.first_time) + " s only in the golden file";
  return why;
}

int sweepJUnit(const std::string& path, const std::string& out_dir, const std::vector<SweepCase>& cases,
               const GatheredTable& table) {
  if (path.empty()) return 0;
  TestSuiteReport suite = ciSuite("simbob sweep " + out_dir);
  std::set<std::string> steps, seeds;
  for (const SweepCase& c : cases) {
    steps.insert(c.dt > 0 ? formatNumber(c.dt) + " s" : "the scene's MaxTimeStep");
    seeds.insert(std::to_string(c.seed));
  }
  auto join = [](const std::set<std::string>& v) {
    std::string out;
    for (const std::string& x : v) out += (out.empty() ? "" : ", ") + x;
    return out;
  };
  suite.properties.push_back({"step", join(steps)});
  suite.properties.push_back({"seed", join(seeds)});
  for (size_t i = 0; i < table.cases.size() && i < cases.size(); ++i) {
    const GatheredCase& g = table.cases[i];
    TestCaseReport c;
    c.classname = testClassName(out_dir);
    c.name = caseDirName(g.index);
    for (const auto& [k, v] : cases[i].vary) c.name += " " + k + "=" + v;
    c.file = cases[i].scene;
    if (g.status == "diverged") {
      c.outcome = TestOutcome::Failed;
      c.type = "diverged";
    } else if (g.status != "ok") {
      c.outcome = TestOutcome::Error;
      c.type = g.status;
    }
    c.message = g.status == "missing" ? "no case.json: the case never ran or did not finish"
                                      : (g.error.empty() ? g.status : g.error);
    if (g.status == "ok") c.message.clear();
    suite.cases.push_back(std::move(c));
  }
  Error err;
  if (!writeJUnit(suite, path, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  return 0;
}

}  // namespace simbob::cli
