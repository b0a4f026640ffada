// simbob batch --golden DIR --bless (docs/ci.md, "Blessing a change"): every change is shown
// before any golden file is rewritten, and a batch in which a scene did not run to the end
// rewrites nothing.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "batch.h"
#include "cli.h"
#include "simbob/tool/files.h"
#include "simbob/values.h"

namespace simbob::cli::batch {

namespace {

// Bodies listed per changed golden file; the rest are counted.
constexpr size_t kMaxBlessBodies = 50;

// "  body Ball: largest difference 0.0123 m (t=0.5 s), 0.002 rad (t=0.61 s)" for each body
// that moved, and the bodies or sample times that came or went.
std::string changeLines(const CompareResult& r) {
  std::string out;
  size_t listed = 0, more = 0;
  for (const BodyDiff& d : r.bodies) {
    if (d.compared > 0 && d.max_pos_err == 0 && d.max_rot_err == 0 && !d.missingRows()) continue;
    if (listed++ >= kMaxBlessBodies) {
      ++more;
      continue;
    }
    out += "  body " + quoteInput(d.body) + ": largest difference " + formatApprox(d.max_pos_err) +
           " m (t=" + formatNumber(d.max_pos_time) + " s), " + formatApprox(d.max_rot_err) +
           " rad (t=" + formatNumber(d.max_rot_time) + " s)" + (d.exceeded() ? ", beyond the tolerances" : "") +
           (d.missingRows() ? ", rows missing" : "") + "\n";
  }
  if (more) out += "  ... and " + countOf(more, "more body", "more bodies") + "\n";
  for (const std::string& b : r.only_actual) out += "  body " + quoteInput(b) + ": new\n";
  for (const std::string& b : r.only_golden) out += "  body " + quoteInput(b) + ": gone\n";
  if (r.times_only_actual.count || r.times_only_golden.count)
    out += "  sample times: " + std::to_string(r.times_only_actual.count) + " new, " +
           std::to_string(r.times_only_golden.count) + " gone (" + std::to_string(r.actual_samples) + " samples now, " +
           std::to_string(r.golden_samples) + " before)\n";
  return out;
}

}  // namespace

int blessFrom(const BatchArgs& a) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(a.bless_from, ec)) {
    g_log.error({ErrorKind::MissingInput, {a.bless_from, 0}, "--bless-from: not a folder (a batch's --out-dir)"});
    return kExitNoInput;
  }
  // Every run's summary: NAME.json beside its trajectory NAME.csv, and NAME.partial.json of a run
  // that failed or was refused: a folder with a run that did not finish blesses nothing.
  std::vector<std::string> files;
  for (fs::directory_iterator it(a.bless_from, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && it->path().extension() == ".json") files.push_back(it->path().string());
  std::sort(files.begin(), files.end());
  std::vector<Job> jobs;
  for (const std::string& f : files) {
    std::ifstream in(f);
    const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
    if (!summary.is_object() || !summary.contains("status") || !summary["status"].is_string()) continue;
    const bool partial = endsWith(f, ".partial.json");
    Job j;
    j.out = partial ? f.substr(0, f.size() - 13) + ".csv" : fs::path(f).replace_extension(".csv").string();
    j.scene = summary.contains("scene") && summary["scene"].is_string() ? summary["scene"].get<std::string>() : j.out;
    const std::string status = summary["status"].get<std::string>();
    if (!partial && status == "completed" && fs::is_regular_file(j.out, ec)) {
      j.status = "ok";
      compareWithGolden(j, a);
    } else {
      j.status = status == "completed" ? "failed" : status;
      if (summary.contains("error") && summary["error"].is_object() && summary["error"].contains("text") &&
          summary["error"]["text"].is_string())
        j.error = summary["error"]["text"].get<std::string>();
      if (j.error.empty()) j.error = "the run did not finish (" + quoteInput(f, 8192) + ")";
    }
    jobs.push_back(std::move(j));
  }
  if (jobs.empty()) {
    g_log.error({ErrorKind::MissingInput,
                 {a.bless_from, 0},
                 "--bless-from: no run summary (NAME.json beside NAME.csv) in the folder"});
    return kExitNoInput;
  }
  g_log.info("--bless-from: " + countOf(jobs.size(), "trajectory", "trajectories") + " in " + a.bless_from);
  return blessGoldens(jobs, a);
}

int blessGoldens(const std::vector<Job>& jobs, const BatchArgs& a) {
  std::vector<const Job*> broken, changed;
  for (const Job& j : jobs) {
    if (j.status != "ok" || j.golden_status == "unreadable")
      broken.push_back(&j);
    else if (j.golden_status == "mismatch" || j.golden_status == "no-golden")
      changed.push_back(&j);
  }
  if (!broken.empty()) {
    const Job& j = *broken.front();
    g_log.error({ErrorKind::Diverged,
                 {},
                 "--bless refused: " + countOf(broken.size(), "scene", "scenes") +
                     " did not run to the end or could not be compared (first: " + quoteInput(j.scene, 8192) + ": " +
                     quoteInput(j.error.empty() ? j.status : j.error, 8192) + "); no golden file was changed"});
    return kExitResultWrong;
  }
  if (changed.empty()) {
    g_log.info("--bless: every golden file in " + a.golden + " matches; nothing to bless");
    return kExitOk;
  }
  // First every change, then the writes: what is shown is all that will happen.
  std::printf("\n--bless: %s change:\n", countOf(changed.size(), "golden file", "golden files").c_str());
  for (const Job* j : changed) {
    if (!j->comparison) {
      std::printf("new      %s (from %s)\n", quoteInput(j->golden_path, 8192).c_str(),
                  quoteInput(j->scene, 8192).c_str());
      continue;
    }
    std::printf("changed  %s (%s):\n%s", quoteInput(j->golden_path, 8192).c_str(), quoteInput(j->scene, 8192).c_str(),
                changeLines(*j->comparison).c_str());
  }
  std::fflush(stdout);
  // The first bless may find no golden folder yet.
  std::error_code dir_ec;
  std::filesystem::create_directories(a.golden, dir_ec);
  if (dir_ec) {
    g_log.error({ErrorKind::CannotCreate, {a.golden, 0}, "cannot create the golden folder: " + dir_ec.message()});
    return kExitCantCreate;
  }
  // All rewritten, or none (commitOutputs puts the old files back if one rename fails).
  std::vector<std::unique_ptr<OutputFile>> files;
  std::vector<OutputFile*> commit;
  Error err;
  for (const Job* j : changed) {
    std::string bytes, reason;
    if (!readFile(j->out, kMaxTrajectoryFileBytes, &bytes, &reason)) {
      g_log.error({ErrorKind::MissingInput, {j->out, 0}, "cannot read it again: " + reason});
      return kExitNoInput;
    }
    files.push_back(OutputFile::open(j->golden_path, &err));
    if (!files.back() || !files.back()->write(bytes)) break;
    commit.push_back(files.back().get());
  }
  if (commit.size() != changed.size() || !commitOutputs(commit, &err)) {
    if (err.message.empty()) err = {ErrorKind::IoError, {changed[commit.size()]->golden_path, 0}, "write failed"};
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  g_log.info("--bless: rewrote " + countOf(changed.size(), "golden file", "golden files") + " in " + a.golden +
             "; review the changes above and commit them");
  return kExitOk;
}

}  // namespace simbob::cli::batch
