#include "cli.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "simbob/tool/document_ini.h"
#include "simbob/tool/frame_sinks.h"
#include "simbob/registry.h"
#include "simbob/values.h"

namespace simbob::cli {

Log g_log;
volatile std::sig_atomic_t g_stop = 0;

namespace {
// What the exit-at-once handler prints; formatted before the handler is installed, since a
// signal handler may only call async-signal-safe functions (write, _exit).
char g_signal_message[2][1024];
size_t g_signal_message_len[2];
volatile std::sig_atomic_t g_signal_exits = 0;
int g_log_fd = -1;

void installHandler(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocking waitpid() returns EINTR
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}
}  // namespace

extern "C" void simbobOnSignal(int sig) {
  g_stop = sig;
  if (g_signal_exits) {
    const int i = sig == SIGTERM ? 1 : 0;
    ssize_t ignored = ::write(2, g_signal_message[i], g_signal_message_len[i]);
    if (g_log_fd >= 0) ignored = ::write(g_log_fd, g_signal_message[i], g_signal_message_len[i]);
    (void)ignored;
    _exit(sig == SIGTERM ? kExitSigTerm : kExitSigInt);
  }
}

void catchStopSignals() {
  g_signal_exits = 0;
  installHandler(simbobOnSignal);
}

void exitOnStopSignals(const std::string& place, const std::string& what) {
  g_signal_exits = 0;
  for (int i = 0; i < 2; ++i) {
    std::string line =
        quoteInput(place, 400) + ": error: interrupted while " + what + " (" + (i == 1 ? "SIGTERM" : "SIGINT") + ")\n";
    if (line.size() > sizeof g_signal_message[i]) line.resize(sizeof g_signal_message[i]);
    std::memcpy(g_signal_message[i], line.data(), line.size());
    g_signal_message_len[i] = line.size();
  }
  g_log_fd = g_log.file ? fileno(g_log.file) : -1;
  g_signal_exits = 1;
  installHandler(simbobOnSignal);
  // A signal that came before this call is not lost.
  if (g_stop) simbobOnSignal(static_cast<int>(g_stop));
}

int stopExitCode() { return g_stop == SIGTERM ? kExitSigTerm : kExitSigInt; }

bool checkTimeOption(const char* name, double seconds) {
  const std::string problem = clockTimeProblem(name, seconds);
  if (problem.empty()) return true;
  g_log.error({ErrorKind::InvalidInput, {}, problem});
  return false;
}

int checkOutputs(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  const Error e = outputCollision(outputs, inputs);
  if (e.message.empty()) return 0;
  closeLogIfInput(inputs);
  g_log.error(e);
  return kExitUsage;
}

void closeLogIfInput(const std::vector<NamedPath>& inputs) {
  if (!g_log.file) return;
  for (const NamedPath& in : inputs)
    if (sameExistingFile(g_log.path, in.path)) {
      std::fclose(g_log.file);  // not one more line into an input
      g_log.file = nullptr;
      return;
    }
}

int checkNotEmpty(const char* option, const std::string& value, bool given) {
  if (!given || !value.empty()) return 0;
  g_log.error({ErrorKind::InvalidInput, {}, std::string(option) + " needs a file name, got \"\""});
  return kExitUsage;
}

std::string jsonText(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
std::string jsonText(const nlohmann::ordered_json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string fixedDecimals(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
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
    case ErrorKind::Interrupted:
      return stopExitCode();
    case ErrorKind::ControllerFailed:
      return kExitControllerFailed;
    case ErrorKind::Internal:
      return kExitSoftware;
    case ErrorKind::Unavailable:
      return kExitUnavailable;
    case ErrorKind::Protocol:
      return kExitProtocol;
    case ErrorKind::Usage:
      return kExitUsage;
  }
  return kExitSoftware;
}

namespace {
std::string place(const Error& e) {
  if (e.loc.file.empty()) return "simbob";
  return e.loc.line > 0 ? e.loc.file + ":" + std::to_string(e.loc.line) : e.loc.file.str();
}
}  // namespace

void Log::write(const std::string& raw, bool to_stderr) {
  // Input echoed in a message without quoteInput (a 50 MB line, a control character) is made
  // printable here; printable UTF-8 passes unchanged.
  const std::string line = quoteInput(raw, kMaxLogLine);
  if (to_stderr) std::fprintf(stderr, "%s\n", line.c_str());
  if (file && write_errno == 0) {
    if (std::fprintf(file, "%s\n", line.c_str()) < 0 || std::fflush(file) != 0) write_errno = errno ? errno : EIO;
  }
}

int Log::close() {
  if (!file) return 0;
  if (std::fclose(file) != 0 && write_errno == 0) write_errno = errno ? errno : EIO;
  file = nullptr;
  g_log_fd = -1;
  if (write_errno == 0) return 0;
  std::fprintf(stderr, "%s: error: writing the log file failed: %s\n", quoteInput(path, 400).c_str(),
               std::strerror(write_errno));
  return kExitIoErr;
}
// "file:line: error: message" so that editors and CI logs can jump to the place.
void Log::error(const Error& e) {
  if (!first_error) first_error = e;
  write(e.errorLine(), true);
}
void Log::warning(const Error& e) { write(place(e) + ": warning: " + e.message, level != Level::Quiet); }
void Log::note(const Error& e) { write(place(e) + ": note: " + e.message, level != Level::Quiet); }
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
    g_log.path = c.log_file;
    g_log.file = std::fopen(c.log_file.c_str(), "a");
    if (!g_log.file) {
      g_log.error(
          {ErrorKind::CannotCreate, {c.log_file, 0}, std::string("cannot open log file: ") + std::strerror(errno)});
      return kExitCantCreate;
    }
  }
  return 0;
}

}  // namespace simbob::cli
