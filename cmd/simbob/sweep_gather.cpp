// simbob sweep gather (the cases' results as one table) and sweep sbatch (Slurm scripts).
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "ci_report.h"
#include "cli.h"
#include "sweep_cli.h"
#include "commands.h"
#include "workers.h"
#include "simbob/tool/csv.h"
#include "simbob/tool/files.h"
#include "simbob/tool/sweep_plan.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::cli::sweep {

namespace fs = std::filesystem;

int sweepGather(const SweepArgs& a) {
  const std::string manifest = (fs::path(a.input) / "manifest.jsonl").string();
  std::string text;
  std::vector<SweepCase> cases;
  int code = 0;
  if (!readManifest(manifest, &text, &cases, &code)) return code;
  const std::string out = a.out.empty() ? (fs::path(a.input) / "results.csv").string() : a.out;
  {
    // The table must not replace what it is gathered from.
    std::vector<NamedPath> inputs = {{"the manifest", manifest}};
    for (const SweepCase& c : cases)
      inputs.push_back({"the case file", (fs::path(a.input) / caseDirName(c.index) / "case.json").string()});
    if (int c = checkOutputs(
            {{a.out.empty() ? "the table" : "-o", out}, {"--junit", a.junit}, {"--log-file", g_log.path}}, inputs))
      return c;
  }
  const GatheredTable table = gatherSweep(a.input, cases);
  std::vector<int> retry;
  size_t ok = 0;
  for (const GatheredCase& c : table.cases) {
    if (c.status == "ok") {
      ++ok;
      continue;
    }
    retry.push_back(c.index);
    if (!a.retry)
      g_log.error({ErrorKind::Diverged,
                   {(fs::path(a.input) / caseDirName(c.index)).string(), 0},
                   quoteInput(c.status) + (c.error.empty() ? "" : ": " + quoteInput(c.error))});
  }
  Error err;
  if (!writeFileAtomically(out, table.csv, &err)) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  if (int c = sweepJUnit(a.junit, a.input, cases, table)) return c;
  if (a.retry) {
    if (!retry.empty()) std::printf("--array=%s\n", arrayList(retry).c_str());
  }
  g_log.info("wrote " + out + ": " + std::to_string(ok) + " of " + std::to_string(cases.size()) + " cases ok" +
             (retry.empty() ? "" : "; to redo: --array=" + arrayList(retry)));
  return retry.empty() ? kExitOk : kExitResultWrong;
}

// Single-quoted for sh.
namespace {

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// The value of an `#SBATCH --opt=VALUE` line as sbatch reads it: it splits the line at blanks
// and ends it at an unquoted '#'; inside "..." blanks and '#' are kept and '\' escapes the next
// character. Plain values stay as they are.
std::string sbatchQuote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.,/:%@+=") ==
                        std::string::npos)
    return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') q += '\\';
    q += ch;
  }
  return q + "\"";
}

// A value that goes into a generated script is one line of text: a newline would end the
// #SBATCH line (sbatch stops reading options there) and start a shell command.
bool scriptValue(const std::string& what, const std::string& value) {
  for (unsigned char ch : value)
    if (ch < 0x20 || ch == 0x7F) {
      g_log.error({ErrorKind::InvalidInput,
                   {},
                   what + " '" + quoteInput(value) +
                       "' holds a control character; it cannot go into a job script (choose another)"});
      return false;
    }
  return true;
}

}  // namespace

int sweepSbatch(const SweepArgs& a, const Common& common) {
  char exe[4096] = {};
  ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
  const std::string binary = n > 0 ? std::string(exe, static_cast<size_t>(n)) : "simbob";
  const std::string out = absolutePath(a.out);
  const std::string manifest = absolutePath(a.input);
  // Checked before anything is written: every value the scripts will hold.
  const std::vector<std::string> options = workerOptions(common);
  if (!scriptValue("--partition", a.partition) || !scriptValue("-o", out) || !scriptValue("the manifest", manifest) ||
      !scriptValue("the simbob binary", binary))
    return kExitUsage;
  std::string forwarded;  // --plugin and --settings, for every case
  for (const std::string& o : options) {
    if (!scriptValue(o.rfind("--", 0) == 0 ? "an option" : "--plugin or --settings", o)) return kExitUsage;
    forwarded += " " + (o.rfind("--", 0) == 0 ? o : shellQuote(o));
  }
  // sbatch's --output reads '%' as a pattern and drops every '\\' (which also turns the
  // patterns off): no folder holding either can be named there.
  if (out.find_first_of("%\\") != std::string::npos) {
    g_log.error({ErrorKind::InvalidInput,
                 {},
                 "-o '" + quoteInput(out) + "' holds '" + out[out.find_first_of("%\\")] +
                     "', which Slurm's --output reads as a file-name pattern (choose another folder)"});
    return kExitUsage;
  }
  std::string text;
  std::vector<SweepCase> cases;
  int code = 0;
  if (!readManifest(a.input, &text, &cases, &code)) return code;
  {
    // The scripts must not replace the manifest they are written for.
    std::vector<NamedPath> outputs;
    for (const char* name : {"sweep.sbatch", "gather.sbatch", "submit.sh"})
      outputs.push_back({std::string("the script"), (fs::path(a.out) / name).string()});
    outputs.push_back({"--log-file", g_log.path});
    if (int c = checkOutputs(outputs, {{"the manifest", a.input}})) return c;
  }
  if (int c = claimOutDir(a.out, text)) return c;
  std::string header = "#!/bin/sh\n";
  auto sbatchLines = [&](const std::string& name, const std::string& log) {
    std::string s = "#SBATCH --job-name=" + name + "\n#SBATCH --output=" + sbatchQuote(out + "/" + log) + "\n";
    if (!a.partition.empty()) s += "#SBATCH --partition=" + sbatchQuote(a.partition) + "\n";
    return s;
  };
  std::string array = "0-" + std::to_string(cases.size() - 1);
  if (a.max_parallel > 0) array += "%" + std::to_string(a.max_parallel);
  const std::string run = header + "# simbob sweep: one case per array task (written by simbob sweep sbatch).\n" +
                          sbatchLines("simbob-sweep", "slurm-%A_%a.out") + "#SBATCH --array=" + array +
                          "\n#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n" + "exec " + shellQuote(binary) +
                          " sweep run " + shellQuote(manifest) + " -o " + shellQuote(out) + forwarded + "\n";
  const std::string gather = header + "# simbob sweep: gather the cases into results.csv (after the array).\n" +
                             sbatchLines("simbob-gather", "slurm-gather-%j.out") + "#SBATCH --ntasks=1\n" + "exec " +
                             shellQuote(binary) + " sweep gather " + shellQuote(out) + "\n";
  const std::string submit =
      header + "# Submits the case array, then gather once every task has ended (afterany).\nset -e\n" +
      "job=$(sbatch --parsable " + shellQuote(out + "/sweep.sbatch") + ")\n" + "job=${job%%;*}\n" +
      "gather=$(sbatch --parsable --dependency=afterany:$job " + shellQuote(out + "/gather.sbatch") + ")\n" +
      "echo \"array job $job, gather job ${gather%%;*}\"\n";
  Error err;
  for (const auto& [name, body] : {std::pair<const char*, const std::string&>{"sweep.sbatch", run},
                                   {"gather.sbatch", gather},
                                   {"submit.sh", submit}}) {
    const std::string path = (fs::path(a.out) / name).string();
    if (!writeFileAtomically(path, body, &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    ::chmod(path.c_str(), 0755);
  }
  std::printf("sh %s/submit.sh\n", shellQuote(out).c_str());
  g_log.info("wrote " + out + "/sweep.sbatch (" + std::to_string(cases.size()) +
             " array tasks), gather.sbatch and "
             "submit.sh; submit with the line above (or: sbatch sweep.sbatch, then sbatch "
             "--dependency=afterany:JOBID gather.sbatch)");
  return kExitOk;
}

}  // namespace simbob::cli::sweep
