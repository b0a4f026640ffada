// simbob: the command-line driver. Decides exit statuses (sysexits.h); the library never exits.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/physics.h"
#include "simbob/registry.h"
#include "simbob/run.h"
#include "simbob/values.h"

namespace {

using namespace simbob;

// Exit statuses (README "Exit statuses").
constexpr int kExitOk = 0;
constexpr int kExitResultWrong = 1;  // diverged run (later: golden mismatch)
constexpr int kExitUsage = 64;       // EX_USAGE
constexpr int kExitDataErr = 65;     // EX_DATAERR: invalid scene
constexpr int kExitNoInput = 66;     // EX_NOINPUT
constexpr int kExitSoftware = 70;    // EX_SOFTWARE: internal error
constexpr int kExitCantCreate = 73;  // EX_CANTCREAT
constexpr int kExitIoErr = 74;       // EX_IOERR
constexpr int kExitSigInt = 130;
constexpr int kExitSigTerm = 143;

volatile std::sig_atomic_t g_stop = 0;
extern "C" void onSignal(int sig) { g_stop = sig; }

int exitCodeFor(ErrorKind k) {
  switch (k) {
    case ErrorKind::InvalidInput: return kExitDataErr;
    case ErrorKind::MissingInput: return kExitNoInput;
    case ErrorKind::CannotCreate: return kExitCantCreate;
    case ErrorKind::IoError: return kExitIoErr;
    case ErrorKind::Diverged: return kExitResultWrong;
    case ErrorKind::Internal: return kExitSoftware;
  }
  return kExitSoftware;
}

enum class Level { Quiet, Normal, Verbose };

struct Log {
  Level level = Level::Normal;
  std::FILE* file = nullptr;

  void write(const char* tag, const std::string& line, bool to_stderr) {
    if (to_stderr) std::fprintf(stderr, "%s%s\n", tag, line.c_str());
    if (file) {
      std::fprintf(file, "%s%s\n", tag, line.c_str());
      std::fflush(file);
    }
  }
  void error(const Error& e) {
    // "file:line: error: message" so editors can jump to the place.
    std::string where = e.loc.file.empty() ? "simbob" : (e.loc.line > 0 ? e.loc.file + ":" + std::to_string(e.loc.line) : e.loc.file);
    write("", where + ": error: " + e.message, true);
  }
  void warning(const Error& e) {
    std::string where = e.loc.file.empty() ? "simbob" : (e.loc.line > 0 ? e.loc.file + ":" + std::to_string(e.loc.line) : e.loc.file);
    write("", where + ": warning: " + e.message, level != Level::Quiet);
  }
  void info(const std::string& s) { write("simbob: ", s, level != Level::Quiet); }
  void debug(const std::string& s) { write("simbob: ", s, level == Level::Verbose); }
};

Log g_log;

// Reports every diagnostic; returns the exit status for the errors (0 if none).
int report(const Diagnostics& d, bool warnings) {
  if (warnings)
    for (const auto& w : d.warnings()) g_log.warning(w);
  int code = 0;
  for (const auto& e : d.errors()) {
    g_log.error(e);
    int c = exitCodeFor(e.kind);
    // A missing input file wins over data errors: nothing else could be checked.
    if (code == 0 || c == kExitNoInput) code = c;
  }
  return code;
}

struct Common {
  bool quiet = false;
  bool verbose = false;
  std::string log_file;
  std::string settings;
};

int setupLogging(const Common& c) {
  g_log.level = c.quiet ? Level::Quiet : (c.verbose ? Level::Verbose : Level::Normal);
  if (!c.log_file.empty()) {
    g_log.file = std::fopen(c.log_file.c_str(), "a");
    if (!g_log.file) {
      g_log.error({ErrorKind::CannotCreate, {c.log_file, 0}, std::string("cannot open log file: ") + std::strerror(errno)});
      return kExitCantCreate;
    }
  }
  return 0;
}

// Global settings INI (guide 3.3.1): LogFile, ExtensionFolder, TextureFolder.
int readSettings(Common& c) {
  if (c.settings.empty()) return 0;
  Scene holder;
  int comp = -1;
  Diagnostics d;
  if (!loadStructIni(c.settings, builtinRegistry(), "GlobalSettings", &holder, &comp, d)) return report(d, true);
  const std::string& log = holder.at(comp).string("LogFile");
  if (c.log_file.empty() && !log.empty()) c.log_file = log;
  return 0;
}

bool loadAndCompile(const std::string& path, Scene* scene, Model* model, int* code, bool warnings) {
  Diagnostics d;
  if (!loadScene(path, builtinRegistry(), scene, d)) {
    *code = report(d, warnings);
    return false;
  }
  if (!compileScene(*scene, model, d)) {
    *code = report(d, warnings);
    return false;
  }
  report(d, warnings);
  return true;
}

class Progress {
 public:
  Progress(double duration, bool enabled) : duration_(duration), enabled_(enabled && isatty(2)) {
    start_ = std::chrono::steady_clock::now();
  }
  void update(double t) {
    if (!enabled_) return;
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (wall < 1.0) return;  // short runs print nothing
    int pct = static_cast<int>(100.0 * t / duration_ + 0.5);
    int bar = pct * 30 / 100;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%% t=%.2f/%.2f s", bar, "##############################", 30 - bar, "", pct, t,
                 duration_);
    shown_ = true;
  }
  void done() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  double duration_;
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

bool writeFileAtomically(const std::string& path, const std::string& text, Error* err) {
  std::string tmp = path + ".tmp." + std::to_string(getpid());
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) {
    *err = {ErrorKind::CannotCreate, {path, 0}, std::string("cannot create: ") + std::strerror(errno)};
    return false;
  }
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  ok = (std::fclose(f) == 0) && ok;
  if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    *err = {ErrorKind::IoError, {path, 0}, std::string("cannot write: ") + std::strerror(errno)};
    return false;
  }
  return true;
}

std::string replaceExtension(const std::string& path, const std::string& ext) {
  std::filesystem::path p(path);
  p.replace_extension(ext);
  return p.string();
}

// ------------------------------------------------------------------ run
struct RunArgs {
  std::string scene;
  double duration = 0;
  double dt = 0;
  double sample_interval = 0.01;
  std::string out;
  uint32_t seed = 0;
  bool json = false;
};

int cmdRun(RunArgs& a) {
  Scene scene;
  Model model;
  int code = 0;
  if (!loadAndCompile(a.scene, &scene, &model, &code, true)) return code;
  if (!(a.duration > 0) || !std::isfinite(a.duration)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--duration must be a positive number of seconds"});
    return kExitUsage;
  }
  if (a.dt < 0 || !std::isfinite(a.dt) || (a.dt > 0 && a.dt < 1e-9)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--dt must be at least 1e-9 s"});
    return kExitUsage;
  }
  if (!(a.sample_interval >= 1e-9) || !std::isfinite(a.sample_interval)) {
    g_log.error({ErrorKind::InvalidInput, {}, "--sample-interval must be at least 1e-9 s"});
    return kExitUsage;
  }
  if (a.out.empty()) a.out = std::filesystem::path(a.scene).stem().string() + ".csv";

  std::vector<std::string> keys;
  for (const auto& b : model.bodies) keys.push_back(b.key);
  Error err;
  std::unique_ptr<TrajectoryWriter> writer = TrajectoryWriter::open(a.out, keys, &err);
  if (!writer) {
    g_log.error(err);
    return exitCodeFor(err.kind);
  }
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  RunOptions opts;
  opts.duration = a.duration;
  opts.dt = a.dt;
  opts.sample_interval = a.sample_interval;
  opts.seed = a.seed;
  opts.stop = &g_stop;
  Progress progress(a.duration, g_log.level != Level::Quiet);
  opts.progress = [&](double t) { progress.update(t); };
  g_log.debug("running " + a.scene + ": " + std::to_string(model.bodies.size()) + " mobile bodies, " +
              std::to_string(model.geoms.size()) + " geoms, " + std::to_string(model.joints.size()) + " joints");
  RunResult r = runModel(model, opts, writer.get());
  progress.done();

  nlohmann::ordered_json summary;
  summary["simbob_version"] = SIMBOB_VERSION;
  summary["physics"] = physicsVersion();
  summary["scene"] = a.scene;
  summary["scene_hash"] = "fnv1a64:" + scene.content_hash;
  summary["status"] = r.status == RunStatus::Completed ? "completed"
                      : r.status == RunStatus::Diverged ? "diverged"
                      : r.status == RunStatus::Interrupted ? "interrupted" : "failed";
  summary["dt"] = r.dt;
  summary["duration"] = a.duration;
  summary["sim_time"] = r.sim_time;
  summary["sample_interval"] = a.sample_interval;
  summary["seed"] = a.seed;
  summary["units"] = {{"time", "s"}, {"position", "m"}, {"orientation", "unit quaternion w x y z"}};
  summary["bodies"] = model.bodies.size();
  summary["steps"] = r.steps;
  summary["samples"] = r.samples;
  summary["wall_seconds"] = r.wall_seconds;
  summary["steps_per_second"] = r.wall_seconds > 0 ? static_cast<double>(r.steps) / r.wall_seconds : 0.0;

  if (r.status == RunStatus::Completed) {
    if (!writer->commit(&err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    summary["trajectory"] = a.out;
    summary["csv_bytes"] = writer->bytesWritten();
    std::string json_path = replaceExtension(a.out, ".json");
    if (!writeFileAtomically(json_path, summary.dump(2) + "\n", &err)) {
      g_log.error(err);
      return exitCodeFor(err.kind);
    }
    if (a.json) std::printf("%s\n", summary.dump(2).c_str());
    g_log.info("wrote " + a.out + " (" + std::to_string(r.samples) + " samples of " +
               std::to_string(model.bodies.size()) + " bodies, " + std::to_string(r.steps) + " steps in " +
               formatNumber(std::round(r.wall_seconds * 1000) / 1000) + " s)");
    return kExitOk;
  }
  // A failed run keeps what it computed, beside the output and never over it.
  std::string partial = partialPath(a.out);
  Error perr;
  if (writer->keepPartial(partial, &perr)) summary["partial_trajectory"] = partial;
  if (a.json) std::printf("%s\n", summary.dump(2).c_str());
  g_log.error(r.error);
  if (!perr.message.empty()) g_log.error(perr);
  else g_log.info("kept the trajectory so far in " + partial);
  if (r.status == RunStatus::Interrupted) return g_stop == SIGTERM ? kExitSigTerm : kExitSigInt;
  return exitCodeFor(r.error.kind);
}

// ------------------------------------------------------------------ check, dump, types
int cmdCheck(const std::string& path) {
  Scene scene;
  Model model;
  int code = 0;
  if (!loadAndCompile(path, &scene, &model, &code, true)) return code;
  g_log.info(path + ": ok (" + std::to_string(model.bodies.size()) + " mobile bodies, " +
             std::to_string(model.geoms.size()) + " geoms, " + std::to_string(model.joints.size()) + " joints)");
  return kExitOk;
}

int cmdDump(const std::string& path, const std::string& format) {
  Scene scene;
  Diagnostics d;
  if (!loadScene(path, builtinRegistry(), &scene, d)) return report(d, true);
  std::string text = writeScene(scene, format == "ini" ? Format::Ini : Format::Xml, true);
  std::fwrite(text.data(), 1, text.size(), stdout);
  return std::fflush(stdout) == 0 ? kExitOk : kExitIoErr;
}

std::string defaultText(const ParamSpec& p) {
  switch (p.kind) {
    case ParamKind::Value: return formatValue(p.type, p.default_value, p.table);
    case ParamKind::Component:
    case ParamKind::Struct: return p.default_type.empty() ? "(none)" : p.default_type;
    case ParamKind::List: return "(empty)";
  }
  return "";
}

std::string typeText(const ParamSpec& p) {
  switch (p.kind) {
    case ParamKind::Value: {
      std::string s = valueTypeName(p.type);
      if (p.table) {
        s += " (";
        for (size_t i = 0; i < p.table->keys.size(); ++i) s += (i ? "|" : "") + std::string(p.table->keys[i].name);
        s += ")";
      }
      return s;
    }
    case ParamKind::Component:
    case ParamKind::List: {
      std::string s = p.kind == ParamKind::List ? "List of " : "";
      for (size_t i = 0; i < p.families.size(); ++i) s += (i ? " | " : "") + std::string(familyName(p.families[i]));
      return s;
    }
    case ParamKind::Struct: return "Struct " + p.struct_type;
  }
  return "";
}

int cmdTypes(bool markdown) {
  const Registry& reg = builtinRegistry();
  std::string out;
  if (markdown) out += "# simbob component types\n\nGenerated by `simbob types --markdown` from the registry.\n";
  for (const TypeSpec& t : reg.types()) {
    std::string aliases;
    for (const auto& a : t.aliases) aliases += (aliases.empty() ? "" : ", ") + a;
    if (markdown) {
      out += "\n## " + t.name + " (" + familyName(t.family) + ")\n\n" + t.doc + "\n";
      if (!aliases.empty()) out += "\nAlso accepted as: " + aliases + ".\n";
      if (t.finished_here) out += "\n*Marked unfinished (\\*) in the original guide; finished in simbob.*\n";
      if (!t.params.empty()) {
        out += "\n| Parameter | Type | Default | Unit | Meaning |\n|---|---|---|---|---|\n";
        for (const auto& p : t.params)
          out += "| " + p.name + " | " + typeText(p) + " | `" + defaultText(p) + "` | " + p.unit + " | " + p.doc + " |\n";
      }
    } else {
      out += t.name + " (" + familyName(t.family) + (aliases.empty() ? "" : "; alias " + aliases) + "): " + t.doc + "\n";
      for (const auto& p : t.params)
        out += "  " + p.name + " : " + typeText(p) + " = " + defaultText(p) + (p.unit.empty() ? "" : " [" + p.unit + "]") +
               "  -- " + p.doc + "\n";
    }
  }
  if (markdown) out += "\n## Macros\n\n| Macro | Creates | Meaning |\n|---|---|---|\n";
  else out += "\nMacros:\n";
  for (const auto& m : reg.macros()) {
    if (markdown) out += "| " + m.name + " | " + m.type + " | " + m.doc + " |\n";
    else out += "  " + m.name + " -> " + m.type + " (" + familyName(m.family) + "): " + m.doc + "\n";
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return kExitOk;
}

void addCommon(CLI::App* app, Common& c) {
  app->add_flag("-q,--quiet", c.quiet, "Print only errors (no progress, no info)");
  app->add_flag("-v,--verbose", c.verbose, "Print debug messages");
  app->add_option("--log-file", c.log_file, "Also append log messages to this file");
  app->add_option("--settings", c.settings, "Global settings INI (LogFile, ExtensionFolder, TextureFolder)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"simbob: headless batch simulator for mobile robots (Simulator Bob scenes on ODE)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("simbob ") + SIMBOB_VERSION);
  Common common;

  RunArgs ra;
  CLI::App* run = app.add_subcommand("run", "Simulate a scene and write its pose trajectory as CSV");
  run->add_option("scene", ra.scene, "Scene file (XML, or INI by extension)")->required();
  run->add_option("--duration", ra.duration, "Simulated seconds")->required();
  run->add_option("--dt", ra.dt, "Step size in s (default: the scene's MaxTimeStep)");
  run->add_option("--out", ra.out, "Trajectory CSV (default: <scene name>.csv); the summary goes beside it as .json");
  run->add_option("--sample-interval", ra.sample_interval, "Simulated seconds between samples (default 0.01)");
  run->add_option("--seed", ra.seed, "Seed of ODE's random generator (default 0)");
  run->add_flag("--json", ra.json, "Print the run summary as JSON on stdout");
  addCommon(run, common);

  std::string check_scene;
  CLI::App* check = app.add_subcommand("check", "Load and validate a scene; report every problem found");
  check->add_option("scene", check_scene, "Scene file")->required();
  addCommon(check, common);

  std::string dump_scene, dump_format = "xml";
  CLI::App* dump = app.add_subcommand("dump", "Print the normalized scene with every default filled in");
  dump->add_option("scene", dump_scene, "Scene file")->required();
  dump->add_option("--format", dump_format, "xml or ini")->check(CLI::IsMember({"xml", "ini"}));
  addCommon(dump, common);

  bool markdown = false;
  CLI::App* types = app.add_subcommand("types", "List every component type with its parameters and defaults");
  types->add_flag("--markdown", markdown, "Markdown tables");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitUsage;
  }
  try {
    if (int c = readSettings(common)) return c;
    if (int c = setupLogging(common)) return c;
    if (*run) return cmdRun(ra);
    if (*check) return cmdCheck(check_scene);
    if (*dump) return cmdDump(dump_scene, dump_format);
    if (*types) return cmdTypes(markdown);
  } catch (const std::exception& e) {
    g_log.error({ErrorKind::Internal, {}, std::string("internal error: ") + e.what()});
    return kExitSoftware;
  }
  return kExitUsage;
}
