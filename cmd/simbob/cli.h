// Shared pieces of the command-line driver: exit statuses, logging, diagnostics reporting.
// Only the CLI decides exit statuses (sysexits.h); the library returns errors as values.
#pragma once

#include <csignal>
#include <nlohmann/json.hpp>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/error.h"
#include "simbob/tool/files.h"
#include "simbob/graph.h"
#include "simbob/options.h"
#include "simbob/overrides.h"

namespace simbob::cli {

// Exit statuses (README "Exit statuses").
constexpr int kExitOk = 0;
constexpr int kExitResultWrong = 1;       // diverged run, golden mismatch, failed scene in a batch
constexpr int kExitControllerFailed = 2;  // a controller or plug-in failed (reported an error, misused the API, threw)
constexpr int kExitUsage = 64;            // EX_USAGE
constexpr int kExitDataErr = 65;          // EX_DATAERR: invalid scene or data file
constexpr int kExitNoInput = 66;          // EX_NOINPUT
constexpr int kExitUnavailable =
    69;  // EX_UNAVAILABLE: a party held the simulation past MaxAccessTime, or a socket peer is not there
constexpr int kExitSoftware = 70;    // EX_SOFTWARE: internal error
constexpr int kExitCantCreate = 73;  // EX_CANTCREAT
constexpr int kExitIoErr = 74;       // EX_IOERR
constexpr int kExitProtocol = 76;    // EX_PROTOCOL: a socket peer broke the protocol
constexpr int kExitSigInt = 130;
constexpr int kExitSigTerm = 143;

int exitCodeFor(ErrorKind k);

enum class Level { Quiet, Normal, Verbose };

/// Log lines go to stderr (by level) and to --log-file (always). Input quoted in a message is
/// shown printable (quoteInput) and a line is cut at kMaxLogLine bytes.
struct Log {
  static constexpr size_t kMaxLogLine = 4096;
  Level level = Level::Normal;
  std::FILE* file = nullptr;
  std::string path;                  ///< of the log file
  int write_errno = 0;               ///< first failed write to the log file
  std::optional<Error> first_error;  ///< the first error reported (run --refusal-summary writes it)

  void error(const Error& e);
  void warning(const Error& e);
  /// "file:line: note: message" (what an import did: simbob check).
  void note(const Error& e);
  void info(const std::string& s);
  void debug(const std::string& s);
  /// Closes the log file; 74 (after saying so on stderr) if a write to it failed, else 0.
  int close();

 private:
  void write(const std::string& raw, bool to_stderr);
};

extern Log g_log;
extern volatile std::sig_atomic_t g_stop;

/// Options every subcommand has.
struct Common {
  bool quiet = false;
  bool verbose = false;
  std::string log_file;
  std::string settings;
  std::vector<std::string> plugins;   ///< --plugin FILE, in order
  std::vector<std::string> packages;  ///< --package NAME=DIR, in order (URDF package:// folders)
  std::string extension_folder;       ///< the global setting ExtensionFolder (--settings)
  std::string texture_folder;         ///< TextureFolder of the global settings (relative to the settings file)
  bool document_ini = false;          ///< DocumentIni of the global settings: read <scene>.ini's cameras
  bool no_controllers = false;        ///< --no-controllers: refuse scenes that start programs
  /// The component types: built once by main (registerBuiltins) and passed down with the options.
  const Registry* registry = nullptr;
};

/// Prints every diagnostic; returns the exit status its errors call for (0 if none).
int report(const Diagnostics& d, bool warnings);
int setupLogging(const Common& c);
int readSettings(Common& c);

using simbob::NamedPath;

/// Appends the files a loaded scene was read from, as inputs no output may replace: the scene,
/// its imports, and the DocumentIni its overrides came from.
void appendSceneInputs(const LoadReport& loaded, const std::string& path, const std::vector<Override>& overrides,
                       std::vector<NamedPath>* inputs);

/// Appends what else a compiled scene reads when it is drawn or set up: every texture file its
/// skins may name (textureFiles) and, with the global setting DocumentIni, the INI beside the scene.
void appendModelInputs(const Model& model, const Common& common, const std::string& scene,
                       std::vector<NamedPath>* inputs);

/// Loads and compiles a scene (loadModel), reporting problems (and, with `warnings`, warnings);
/// *code is the exit status on failure. The log file must not be any file read (the scene, its
/// imports, `inputs`): nothing is appended to an input, and that is a usage error. With
/// `collect_all` (simbob check), a scene that failed to load is compiled too, so that one pass
/// reports every problem the compile step can still see. `overrides` (--set, a DocumentIni)
/// change the graph between loading and compiling.
bool loadAndCompile(const std::string& path, const Registry& reg, Model* model, LoadReport* loaded, int* code,
                    bool warnings, bool collect_all, const std::vector<NamedPath>& inputs = {},
                    const std::vector<Override>& overrides = {});

/// The `--set` options as overrides; a malformed one is reported (usage error, 64).
int parseSetOptions(const std::vector<std::string>& sets, std::vector<Override>* out);

/// The overrides of a scene: with the global setting DocumentIni, the camera settings of the INI
/// beside the scene (docs/recording.md, "DocumentIni"), then the `--set` options (which win). Appends to out;
/// returns 0 or the exit status of the error it reported.
int sceneOverrides(const Common& c, const std::string& scene, const std::vector<std::string>& sets,
                   std::vector<Override>* out);

/// JSON text of a report or summary; invalid UTF-8 (from keys in input files) is replaced, never
/// thrown.
std::string jsonText(const nlohmann::json& j);
std::string jsonText(const nlohmann::ordered_json& j);

/// `v` with exactly `decimals` digits after the point ("1.50"), for tables and progress lines.
std::string fixedDecimals(double v, int decimals);

bool endsWith(const std::string& s, const std::string& suffix);

/// SIGINT/SIGTERM set g_stop, for a loop that stops by itself. Blocking calls (waitpid) return
/// EINTR instead of being restarted.
void catchStopSignals();

/// SIGINT/SIGTERM end the process at once: "PLACE: error: interrupted while WHAT" on stderr and
/// in the log file, exit 130/143. For stretches with nothing to keep (loading a scene).
void exitOnStopSignals(const std::string& place, const std::string& what);

/// 130 or 143 after SIGINT or SIGTERM (g_stop).
int stopExitCode();

/// Time options (--duration, --dt, --sample-interval) lie in [kMinClockTime, kMaxClockTime]
/// seconds (clockTimeProblem): the clock counts integer nanoseconds in 64 bits. Returns false
/// after reporting.
bool checkTimeOption(const char* name, double seconds);

/// A usage error (reported, 64) if an output names an input of the command by any spelling,
/// or two outputs would be the same file; 0 otherwise. Streams (/dev/null, "-") never collide.
int checkOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);

/// Stops writing the log file (--log-file) when it is one of `inputs`: nothing is appended to an input.
void closeLogIfInput(const std::vector<NamedPath>& inputs);

/// A usage error (reported, 64) if an output option was given as "".
int checkNotEmpty(const char* option, const std::string& value, bool given);

}  // namespace simbob::cli
