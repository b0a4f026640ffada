// Shared pieces of the command-line driver: exit statuses, logging, diagnostics reporting.
// Only the CLI decides exit statuses (sysexits.h); the library returns errors as values.
#pragma once

#include <csignal>
#include <nlohmann/json.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/error.h"
#include "simbob/files.h"
#include "simbob/graph.h"

namespace simbob::cli {

// Exit statuses (README "Exit statuses").
constexpr int kExitOk = 0;
constexpr int kExitResultWrong = 1;  // diverged run, golden mismatch, failed scene in a batch
constexpr int kExitUsage = 64;       // EX_USAGE
constexpr int kExitDataErr = 65;     // EX_DATAERR: invalid scene or data file
constexpr int kExitNoInput = 66;     // EX_NOINPUT
constexpr int kExitSoftware = 70;    // EX_SOFTWARE: internal error
constexpr int kExitCantCreate = 73;  // EX_CANTCREAT
constexpr int kExitIoErr = 74;       // EX_IOERR
constexpr int kExitSigInt = 130;
constexpr int kExitSigTerm = 143;

int exitCodeFor(ErrorKind k);

enum class Level { Quiet, Normal, Verbose };

/// Log lines go to stderr (by level) and to --log-file (always).
struct Log {
  Level level = Level::Normal;
  std::FILE* file = nullptr;

  void error(const Error& e);
  void warning(const Error& e);
  void info(const std::string& s);
  void debug(const std::string& s);

 private:
  void write(const std::string& line, bool to_stderr);
};

extern Log g_log;
extern volatile std::sig_atomic_t g_stop;

/// Options every subcommand has.
struct Common {
  bool quiet = false;
  bool verbose = false;
  std::string log_file;
  std::string settings;
};

/// Prints every diagnostic; returns the exit status its errors call for (0 if none).
int report(const Diagnostics& d, bool warnings);
int setupLogging(const Common& c);
int readSettings(Common& c, const Registry& reg);

/// Load and compile a scene, reporting problems; *code is the exit status on failure. With
/// `collect_all` (simbob check), a scene that failed to load is compiled too, so that one pass
/// reports every problem the compile step can still see.
bool loadAndCompile(const std::string& path, const Registry& reg, Scene* scene, Model* model, int* code, bool warnings,
                    bool collect_all = false);

/// JSON text of a report or summary; invalid UTF-8 (from keys in input files) is replaced, never
/// thrown.
std::string jsonText(const nlohmann::json& j);
std::string jsonText(const nlohmann::ordered_json& j);

bool endsWith(const std::string& s, const std::string& suffix);

/// Install SIGINT/SIGTERM handlers that set g_stop.
void catchStopSignals();

}  // namespace simbob::cli
