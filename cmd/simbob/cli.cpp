#include "cli.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "components/families.h"
#include "simbob/registry.h"

namespace simbob::cli {

Log g_log;
volatile std::sig_atomic_t g_stop = 0;

extern "C" void simbobOnSignal(int sig) { g_stop = sig; }

void catchStopSignals() {
  std::signal(SIGINT, simbobOnSignal);
  std::signal(SIGTERM, simbobOnSignal);
}

std::string jsonText(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
std::string jsonText(const nlohmann::ordered_json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int exitCodeFor(ErrorKind k) {
  switch (k) {
    case ErrorKind::InvalidInput:
      return kExitDataErr;
    case ErrorKind::MissingInput:
      return kExitNoInput;
    case ErrorKind::CannotCreate:
      return kExitCantCreate;
    case ErrorKind::IoError:
      return kExitIoErr;
    case ErrorKind::Diverged:
      return kExitResultWrong;
    case ErrorKind::Internal:
      return kExitSoftware;
  }
  return kExitSoftware;
}

namespace {
std::string place(const Error& e) {
  if (e.loc.file.empty()) return "simbob";
  return e.loc.line > 0 ? e.loc.file + ":" + std::to_string(e.loc.line) : e.loc.file.str();
}
}  // namespace

void Log::write(const std::string& line, bool to_stderr) {
  if (to_stderr) std::fprintf(stderr, "%s\n", line.c_str());
  if (file) {
    std::fprintf(file, "%s\n", line.c_str());
    std::fflush(file);
  }
}
// "file:line: error: message" so that editors and CI logs can jump to the place.
void Log::error(const Error& e) { write(place(e) + ": error: " + e.message, true); }
void Log::warning(const Error& e) { write(place(e) + ": warning: " + e.message, level != Level::Quiet); }
void Log::info(const std::string& s) { write("simbob: " + s, level != Level::Quiet); }
void Log::debug(const std::string& s) { write("simbob: " + s, level == Level::Verbose); }

int report(const Diagnostics& d, bool warnings) {
  if (warnings)
    for (const auto& w : d.warnings()) g_log.warning(w);
  int code = 0;
  for (const auto& e : d.errors()) {
    g_log.error(e);
    int c = exitCodeFor(e.kind);
    // A missing input file wins over data errors: nothing behind it could be checked.
    if (code == 0 || c == kExitNoInput) code = c;
  }
  return code;
}

int setupLogging(const Common& c) {
  g_log.level = c.quiet ? Level::Quiet : (c.verbose ? Level::Verbose : Level::Normal);
  if (!c.log_file.empty()) {
    g_log.file = std::fopen(c.log_file.c_str(), "a");
    if (!g_log.file) {
      g_log.error(
          {ErrorKind::CannotCreate, {c.log_file, 0}, std::string("cannot open log file: ") + std::strerror(errno)});
      return kExitCantCreate;
    }
  }
  return 0;
}

int readSettings(Common& c, const Registry& reg) {
  if (c.settings.empty()) return 0;
  Scene holder;
  int comp = -1;
  Diagnostics d;
  if (!loadStructIni(c.settings, reg, "GlobalSettings", &holder, &comp, d)) return report(d, true);
  const std::string& log = holder.at(comp).get(kLogFileParam);
  if (c.log_file.empty() && !log.empty()) c.log_file = log;
  return 0;
}

bool loadAndCompile(const std::string& path, const Registry& reg, Scene* scene, Model* model, int* code, bool warnings,
                    bool collect_all) {
  Diagnostics d;
  bool loaded = loadScene(path, reg, scene, d);
  // A scene that failed to load is still a consistent graph (bad links are empty), so `check`
  // compiles it too and reports what the compile step finds in the same pass.
  bool compiled = (loaded || (collect_all && !scene->comps.empty())) && compileScene(*scene, model, d);
  if (!loaded || !compiled) {
    *code = report(d, warnings);
    return false;
  }
  report(d, warnings);
  return true;
}

}  // namespace simbob::cli
