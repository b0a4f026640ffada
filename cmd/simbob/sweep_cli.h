// simbob sweep, shared between its files (sweep.cpp: plan and the command; sweep_run.cpp: run;
// sweep_gather.cpp: gather and sbatch).
#pragma once

#include <string>
#include <vector>

#include "cli.h"
#include "commands.h"
#include "simbob/tool/sweep_plan.h"

namespace simbob::cli::sweep {

/// The largest manifest read (1 GiB).
inline constexpr size_t kMaxManifestBytes = size_t{1} << 30;

/// Reads `path` (at most 1 GiB) into *text; reports and sets *code (66, or 65 when too large).
bool readInput(const std::string& path, const char* what, std::string* text, int* code);
/// Reads and parses a case manifest; reports and sets *code on failure.
bool readManifest(const std::string& path, std::string* text, std::vector<SweepCase>* cases, int* code);

/// OUT/manifest.jsonl is the manifest the cases in OUT came from: written by the first task,
/// checked by every other, so two sweeps never mix in one folder. 0, or the exit status.
int claimOutDir(const std::string& out, const std::string& manifest_text);

int sweepRun(const SweepArgs& a, const Common& common);
int sweepGather(const SweepArgs& a);
int sweepSbatch(const SweepArgs& a, const Common& common);

}  // namespace simbob::cli::sweep
