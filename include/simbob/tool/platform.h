// What a build and the machine it runs on are, for run summaries, `simbob --version` and CI
// reports (docs/ci.md says which of these the trajectory bytes depend on).
#pragma once

#include <string>

namespace simbob {

/// The compiler simbob was built with: "gcc 12.2.0", "clang 14.0.6".
std::string compilerVersion();

/// The C library running now (it provides libm, whose results the bytes depend on): "glibc 2.36".
std::string libcVersion();

/// The CPU's "model name" from /proc/cpuinfo ("AMD EPYC 7763 64-Core Processor"), "unknown" if
/// none is given. The bytes do not depend on it; a report records it to show they did not.
std::string cpuModel();

}  // namespace simbob

namespace simbob {

/// Opens one of simbob's own on-demand modules (libsimbob_video.so, libsimbob_mesh.so, ...): the
/// libraries behind them (FFmpeg, assimp, cairo, urdfdom) are loaded only by a run that needs
/// them, so every other run starts without their relocations and memory. `env`, when set and not
/// empty, names the file; otherwise the module is looked for beside the executable, one folder up
/// (tests and benchmarks in the build tree), and in ../lib/simbob (an installed simbob). Returns
/// the address of the module's function `entry`, or nullptr with `why` set. Callers keep what
/// they get (see openModuleTable).
void* openSimbobModule(const char* file_name, const char* env, const char* entry, std::string* why);

/// The table a module's `entry` function (`extern "C" const Table* entry()`) returns, or nullptr
/// with `why` set. The function is called through its own type (UBSan's -fsanitize=function
/// checks that).
template <class Table>
const Table* openModuleTable(const char* file_name, const char* env, const char* entry, std::string* why) {
  void* symbol = openSimbobModule(file_name, env, entry, why);
  if (!symbol) return nullptr;
  const Table* table = reinterpret_cast<const Table* (*)()>(symbol)();
  if (!table) *why = std::string(file_name) + ": " + entry + " gave no table";
  return table;
}

}  // namespace simbob
