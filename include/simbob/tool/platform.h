// What a build and the machine it runs on are, for run summaries, `simbob --version` and CI
// reports (docs/ci.md says which of these the trajectory bytes depend on).
#pragma once

#include <mutex>
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

/// Opens one of simbob's own on-demand modules (libsimbob_video.so): the library behind it
/// (FFmpeg) is loaded only by a run that needs it. `env`, when set and not
/// empty, names the file; otherwise the module is looked for beside the executable (the build
/// tree, whose tests/ and bench/ hold links to the modules) and in ../lib/simbob (an installed
/// simbob), never in the folder above the executable. A module that any user can write, or whose
/// folder any user can write, is not opened. Returns the address of the module's function
/// `entry`, or nullptr with `why` set. See simbobModule.
void* openSimbobModule(const char* file_name, const char* env, const char* entry, std::string* why);

/// The table of one module, opened on the first call and remembered (thread-safe): `entry` is
/// the module's `extern "C" const Table* entry()`, called through its own type (UBSan's
/// -fsanitize=function checks that); `linked`, when not null, is that function linked into this
/// program (the Python module links some modules' code in), taken instead of opening the file.
/// A table of another `abi` is refused. Nullptr with `why` set ("<needs>: <why not>").
template <class Table>
const Table* simbobModule(const char* file_name, const char* env, const char* entry, int abi, const char* needs,
                          const Table* (*linked)(), std::string* why) {
  static std::once_flag once;
  static const Table* module = nullptr;
  static std::string error;
  std::call_once(once, [&] {
    const Table* table = nullptr;
    std::string not_found;
    if (linked) {
      table = linked();
    } else if (void* symbol = openSimbobModule(file_name, env, entry, &not_found)) {
      table = reinterpret_cast<const Table* (*)()>(symbol)();
      if (!table) not_found = std::string(file_name) + ": " + entry + " gave no table";
    }
    if (!table)
      error = std::string(needs) + ": " + not_found;
    else if (table->abi != abi)
      error = std::string(file_name) + " is not this build's module (of another ABI)";
    else
      module = table;
  });
  if (!module && why) *why = error;
  return module;
}

}  // namespace simbob
