// simbob batch: its jobs -- scenes, globs and manifest lines -- and the files they write.
#include <glob.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <CLI/CLI.hpp>

#include "batch.h"
#include "simbob/tool/files.h"
#include "simbob/values.h"

namespace simbob::cli::batch {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> splitArgs(const std::string& line, std::string* err) {
  std::vector<std::string> out;
  std::string cur;
  bool in_quotes = false, have = false;
  for (char c : line) {
    if (c == '"') {
      in_quotes = !in_quotes;
      have = true;
    } else if (!in_quotes && (c == ' ' || c == '\t' || c == '\r')) {
      if (have) out.push_back(cur);
      cur.clear();
      have = false;
    } else {
      cur += c;
      have = true;
    }
  }
  if (in_quotes) *err = "unterminated quote";
  if (have) out.push_back(cur);
  return out;
}

std::vector<std::string> expandGlob(const std::string& pattern) {
  glob_t g{};
  std::vector<std::string> out;
  if (glob(pattern.c_str(), 0, nullptr, &g) == 0)
    for (size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);  // glob sorts
  globfree(&g);
  if (out.empty()) out.push_back(pattern);  // a plain path: let the worker report it if missing
  return out;
}

std::string manifestLineProblem(const std::vector<std::string>& words, const BatchArgs& a) {
  std::vector<std::string> args = {words[0], "--duration", formatNumber(a.duration), "--sample-interval",
                                   formatNumber(a.sample_interval)};
  if (a.dt > 0) {
    args.emplace_back("--dt");
    args.push_back(formatNumber(a.dt));
  }
  args.insert(args.end(), words.begin() + 1, words.end());
  CLI::App app{"run"};
  RunArgs ra;
  Common common;
  addRunOptions(&app, ra, common);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return std::string("run options: ") + e.what();
  }
  if (app.count("--out") > 0 && ra.run.out.empty()) return "--out needs a file name, got \"\"";
  return runArgsProblem(ra);
}

// An output of the batch must not be any input (a scene, the manifest, a golden file), nor
// another output. Inputs are compared by device and inode, outputs by their resolved place.
int checkBatchFiles(const std::vector<Job>& jobs, const BatchArgs& a, const Common& common) {
  std::map<std::pair<dev_t, ino_t>, std::string> inputs;
  auto addInput = [&](const std::string& what, const std::string& path) {
    struct stat st {};
    if (!path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode))
      inputs.emplace(std::make_pair(st.st_dev, st.st_ino), what + " " + path);
  };
  addInput("the manifest", a.manifest);
  addInput("--settings", common.settings);
  for (const Job& j : jobs) {
    addInput("the scene", j.scene);
    if (!a.golden.empty()) addInput("the golden file", (fs::path(a.golden) / fs::path(j.out).filename()).string());
  }
  std::vector<NamedPath> outputs = {
      {"--report", a.report},
      {"--log-file", g_log.path},
      {"--junit", a.junit},
      {"--summary-md", a.summary_md},
      {"the artifacts index", a.artifacts.empty() ? "" : (fs::path(a.artifacts) / "index.html").string()}};
  for (const Job& j : jobs) {
    outputs.push_back({"the trajectory", j.out});
    outputs.push_back({"the worker log", j.log});
    outputs.push_back({"the summary", fs::path(j.out).replace_extension(".json").string()});
    if (a.html) outputs.push_back({"the replay page", fs::path(j.out).replace_extension(".html").string()});
    if (!a.golden.empty())
      outputs.push_back({"the comparison report", fs::path(j.out).replace_extension(".compare.txt").string()});
  }
  std::map<std::string, std::string> places;
  for (const NamedPath& o : outputs) {
    if (o.path.empty() || isStreamOutput(o.path)) continue;
    struct stat st {};
    if (::stat(o.path.c_str(), &st) == 0) {
      auto it = inputs.find({st.st_dev, st.st_ino});
      if (it != inputs.end()) {
        g_log.error({ErrorKind::InvalidInput,
                     {},
                     o.what + " " + o.path + " is " + it->second + ": an output must not overwrite an input"});
        return kExitUsage;
      }
    }
    std::error_code ec;
    std::string place = fs::weakly_canonical(fs::absolute(o.path), ec).string();
    if (ec) place = o.path;
    auto [it, fresh] = places.emplace(place, o.what + " " + o.path);
    if (!fresh) {
      g_log.error({ErrorKind::InvalidInput,
                   {},
                   o.what + " " + o.path + " and " + it->second +
                       " are the same file: outputs of one command must not collide"});
      return kExitUsage;
    }
  }
  return 0;
}

// The scenes of --manifest FILE, one per line with `simbob run` options; paths are relative to
// the manifest's folder. 0, or the exit status (reported).
int readManifest(const BatchArgs& a, std::vector<Job>* jobs) {
  if (a.manifest.empty()) return 0;
  std::ifstream in(a.manifest);
  std::error_code dir_ec;
  if (fs::is_directory(a.manifest, dir_ec)) {
    g_log.error({ErrorKind::MissingInput, {a.manifest, 0}, "cannot read manifest: is a directory"});
    return kExitNoInput;
  }
  if (!in) {
    g_log.error(
        {ErrorKind::MissingInput, {a.manifest, 0}, std::string("cannot read manifest: ") + std::strerror(errno)});
    return kExitNoInput;
  }
  fs::path base = fs::path(a.manifest).parent_path();
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find('\0') != std::string::npos) {
      g_log.error({ErrorKind::InvalidInput,
                   {a.manifest, line_no},
                   "the line holds a NUL character, which no scene path or option can hold"});
      return kExitDataErr;
    }
    size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::string err;
    std::vector<std::string> words = splitArgs(line, &err);
    if (!err.empty()) {
      g_log.error({ErrorKind::InvalidInput, {a.manifest, line_no}, err});
      return kExitDataErr;
    }
    if (words.empty()) continue;
    // Scenes in a manifest are relative to the manifest's folder.
    fs::path scene = words[0];
    if (scene.is_relative()) scene = base / scene;
    Job j;
    j.scene = scene.string();
    j.args.assign(words.begin() + 1, words.end());
    j.loc = {a.manifest, line_no};
    // The worker would say only "Run with --help": check the line here and name it.
    if (std::string problem = manifestLineProblem(words, a); !problem.empty()) {
      g_log.error({ErrorKind::InvalidInput, j.loc, problem});
      return kExitDataErr;
    }
    for (size_t i = 0; i + 1 < j.args.size(); ++i)
      if (j.args[i] == "--out") {
        fs::path out = j.args[i + 1];
        if (out.is_relative()) out = base / out;
        j.out = out.string();
        j.args.erase(j.args.begin() + static_cast<long>(i), j.args.begin() + static_cast<long>(i) + 2);
        break;
      }
    jobs->push_back(std::move(j));
  }
  return 0;
}

}  // namespace

int readJobs(const BatchArgs& a, std::vector<Job>* jobs) {
  for (const auto& pattern : a.scenes)
    for (const auto& path : expandGlob(pattern)) {
      Job j;
      j.scene = path;
      jobs->push_back(std::move(j));
    }
  if (int c = readManifest(a, jobs)) return c;
  if (jobs->empty()) {
    g_log.error({ErrorKind::Usage, {}, "no scenes given (name scene files, globs, or --manifest FILE)"});
    return kExitUsage;
  }
  return 0;
}

int assignOutputs(const BatchArgs& a, const Common& common, std::vector<Job>* jobs) {
  std::error_code ec;
  fs::create_directories(a.out_dir, ec);
  if (ec) {
    g_log.error({ErrorKind::CannotCreate, {a.out_dir, 0}, "cannot create output folder: " + ec.message()});
    return kExitCantCreate;
  }
  std::map<std::string, size_t> outs;
  for (size_t i = 0; i < jobs->size(); ++i) {
    Job& j = (*jobs)[i];
    if (j.out.empty()) j.out = (fs::path(a.out_dir) / fs::path(j.scene).stem()).string() + ".csv";
    j.log = fs::path(j.out).replace_extension(".log").string();
    auto [it, fresh] = outs.emplace(j.out, i);
    if (!fresh) {
      g_log.error({ErrorKind::InvalidInput, j.loc,
                   "scenes " + quoteInput((*jobs)[it->second].scene, 8192) + " and " + quoteInput(j.scene, 8192) +
                       " would both write " + quoteInput(j.out, 8192) + "; give one of them --out"});
      return kExitUsage;
    }
  }
  return checkBatchFiles(*jobs, a, common);
}

}  // namespace simbob::cli::batch
