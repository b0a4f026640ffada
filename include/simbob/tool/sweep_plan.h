// Parameter sweeps (docs/sweeps.md): a sweep description (JSON) expands into numbered cases,
// written as a manifest (JSON lines, one case per line); each case runs on its own (a Slurm
// array task, a local worker) into OUT/case-NNNN/, and gather merges the results into a table.
// Plain data and text only: no ODE, no processes (cmd/simbob/sweep.cpp runs them).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "simbob/error.h"
#include "simbob/trajectory.h"

namespace simbob {

/// An end metric of a case, computed from its trajectory: `stat` of coordinate `value` of body
/// `body` over the run. stat: final, initial, max, min, delta (final - initial).
struct SweepMetric {
  std::string name;         ///< column name in the gathered table
  std::string body;         ///< fully qualified body key, as in the CSV
  std::string value = "x";  ///< x, y or z (m)
  std::string stat = "final";
};

/// One case: everything `simbob sweep run` needs, self-contained.
struct SweepCase {
  int index = 0;
  std::string scene;  ///< relative to the manifest's folder (or absolute)
  double duration = 0;
  double dt = 0;  ///< 0 = the scene's MaxTimeStep
  double sample_interval = 0.01;
  uint32_t seed = 0;
  std::vector<std::pair<std::string, std::string>> vary;  ///< varied name -> value text, in column order
  std::vector<std::string> set;                           ///< overrides KEY.PARAM=VALUE: fixed, then varied
  std::vector<SweepMetric> metrics;
};

/// Reads a sweep description and expands it into cases, numbered from 0 in a fixed order
/// (grid: the first `vary` entry changes slowest). `scene_rel` is the base scene's path as the
/// manifest should name it. Errors: "FILE:LINE: ..." for JSON syntax, "FILE: vary[1]: ..."
/// for what the JSON says.
bool planSweep(const std::string& text, const std::string& path, const std::string& scene_rel,
               std::vector<SweepCase>* cases, Error* err);

/// The base scene a sweep description names, as written (relative to the description's folder).
bool sweepScene(const std::string& text, const std::string& path, std::string* scene, Error* err);

/// One manifest line (compact JSON, no newline). Same case -> same bytes.
std::string manifestLine(const SweepCase& c);

/// Parses a manifest; errors name the line ("MANIFEST:3: ...").
bool parseManifest(const std::string& text, const std::string& path, std::vector<SweepCase>* cases, Error* err);

/// The metrics of a finished case from its trajectory; false with *error (naming the metric and
/// the nearest body key) when a body is not in it.
bool computeMetrics(const Trajectory& t, const std::vector<SweepMetric>& metrics, std::vector<double>* values,
                    std::string* error);

/// One metric against one parameter from a gathered table (`simbob plot --x --y`): the rows
/// whose status is ok, sorted by x, as a trajectory of one "body" named y_col whose x
/// coordinate is the metric and whose time is the parameter. Errors name the table and line.
bool sweepTableSeries(const std::string& text, const std::string& path, const std::string& x_col,
                      const std::string& y_col, Trajectory* out, Error* err);

/// What `sweep gather` found of one case in OUT/case-NNNN/case.json.
struct GatheredCase {
  int index = 0;
  std::string status = "missing";  ///< ok, failed, diverged, missing
  std::string error;               ///< why it is not ok ("" when ok or missing)
};

/// The gathered table of a sweep's cases (docs/sweeps.md): one row per case with its varied
/// parameters, seed, status, wall time and metrics, and what each case's case.json says. A case
/// file that cannot be read or holds a field of the wrong type makes that case failed, never
/// the gather.
struct GatheredTable {
  std::string csv;
  std::vector<GatheredCase> cases;
};
GatheredTable gatherSweep(const std::string& out_dir, const std::vector<SweepCase>& cases);

/// OUT/case-NNNN/case.json of a finished case (docs/sweeps.md): status (exit status 0 ok, 1
/// diverged, else failed), error, wall time, parameters and, for an ok case, the metrics computed
/// from DIR/trajectory.csv -- a metric that cannot be computed makes the case failed (exit 65).
nlohmann::ordered_json sweepCaseRecord(const SweepCase& c, const std::string& dir, int exit_code,
                                       const std::string& error, double wall);

/// "case-0007": a case's directory below OUT (at least four digits).
std::string caseDirName(int index);

/// Slurm's --array list of indices: "3,17,42".
std::string arrayList(const std::vector<int>& indices);

}  // namespace simbob
