// What CI reports of batch, compare and sweep gather share (docs/ci.md): the build and machine
// a report was made on, and the names of its test cases.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "simbob/tool/comparison.h"
#include "simbob/tool/test_report.h"

namespace simbob {
struct SweepCase;
struct GatheredTable;
}  // namespace simbob

namespace simbob::cli {

/// A suite named `name` with the timestamp, the host name and the properties every report
/// carries: simbob's version and git revision, ODE's version and configuration, the compiler,
/// the C library and the CPU model.
TestSuiteReport ciSuite(const std::string& name);

/// "scenes.chain" for "scenes/chain.xml" (and for "./scenes/chain.xml"): the path without its
/// extension, '/' as '.'; an absolute path loses its leading '/'.
std::string testClassName(const std::string& path);

/// A failed comparison's one line: the first divergence (time, body, position and rotation error
/// against the tolerances), or the first structural difference.
std::string divergenceMessage(const CompareResult& r);

/// `sweep gather --junit PATH`: one test case per sweep case (ok passes, diverged fails, failed
/// and missing are errors). 0 when `path` is empty or the report was written, else the exit
/// status (reported).
int sweepJUnit(const std::string& path, const std::string& out_dir, const std::vector<SweepCase>& cases,
               const GatheredTable& table);

}  // namespace simbob::cli
