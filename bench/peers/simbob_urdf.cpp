// simbob's side of bench/peers (issue 42): a scene or a bare robot.urdf through the Simulation
// API (as `simbob run` runs it, without trajectory sampling or output), stepped at 1 ms; prints,
// as one JSON line, the process CPU time of the load (read, compile, and the ODE world built by
// the first step(0), which serves t = 0: the median of the loads) and of the steps alone, with the joint angles at the end. The twin of
// mujoco_urdf.cpp; run by bench/peers/run.py (bench/README.md, "Peers").
//
// Usage: simbob_urdf FILE STEPS [--loads K]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "simbob/registry.h"
#include "simbob/simulation.h"

namespace {

double cpuNow() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double wallNow() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: simbob_urdf FILE STEPS [--loads K]\n");
    return 64;
  }
  const std::string file = argv[1];
  const long steps = std::atol(argv[2]);
  int loads = 5;
  for (int i = 3; i < argc; ++i) {
    if (std::strcmp(argv[i], "--loads") == 0 && i + 1 < argc) {
      loads = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "simbob_urdf: unknown argument '%s'\n", argv[i]);
      return 64;
    }
  }
  simbob::Registry reg;
  if (!simbob::registerBuiltins(reg)) return 70;
  simbob::SimulationOptions opts;
  opts.dt = 0.001;
  std::vector<double> load_cpu, load_wall;
  std::unique_ptr<simbob::Simulation> sim;
  for (int k = 0; k < loads; ++k) {
    sim.reset();
    simbob::Diagnostics diag;
    const double c0 = cpuNow(), w0 = wallNow();
    sim = simbob::Simulation::fromFile(file, reg, opts, diag);
    if (!sim) {
      std::fprintf(stderr, "simbob_urdf: %s\n", diag.errors().empty() ? "?" : diag.errors()[0].str().c_str());
      return 65;
    }
    if (!sim->step(0)) {
      std::fprintf(stderr, "simbob_urdf: %s: the world was not built\n", file.c_str());
      return 70;
    }
    load_cpu.push_back(cpuNow() - c0);
    load_wall.push_back(wallNow() - w0);
  }
  const double c0 = cpuNow(), w0 = wallNow();
  // One step a call, to count the contacts each step made (Simulation::step(n) steps one at a
  // time too; a call serves nothing more than the instant it reaches).
  bool ok = true;
  long contacts = 0;
  for (long s = 0; s < steps && ok; ++s) {
    ok = sim->step(1);
    contacts += sim->world().lastContactCount();
  }
  const double step_cpu = cpuNow() - c0, step_wall = wallNow() - w0;
  const simbob::Model& model = sim->model();
  std::printf(
      "{\"engine\": \"simbob\", \"file\": \"%s\", \"nbody\": %zu, \"njnt\": %zu, \"load_cpu_s\": %.6g, "
      "\"load_first_cpu_s\": %.6g, "
      "\"load_wall_s\": %.6g, \"steps\": %llu, \"step_cpu_s\": %.6g, \"step_wall_s\": %.6g, \"contacts\": %ld, "
      "\"time\": %.6g, \"finite\": %s, \"qpos\": {",
      file.c_str(), model.bodies.size(), model.joints.size(), median(load_cpu), load_cpu.front(), median(load_wall),
      static_cast<unsigned long long>(sim->steps()), step_cpu, step_wall, contacts, sim->time(), ok ? "true" : "false");
  for (size_t j = 0; j < model.joints.size(); ++j) {
    const double q = sim->world().joint(static_cast<int>(j)).position;
    std::printf("%s\"%s\": %.6f", j ? ", " : "", model.joints[j].key.c_str(), std::isfinite(q) ? q : 0.0);
  }
  std::printf("}, \"solver\": \"%s\", \"iterations\": %d}\n", model.settings.quickstep ? "QuickStep" : "Step",
              model.settings.quickstep ? model.settings.iterations : 0);
  return ok ? 0 : 1;
}
