// Load time of URDF robots (issue 28): simbob's whole load of a bare robot.urdf (read, urdfdom
// parse, pugixml walk for lines and ignored elements, package:// paths, meshes, planning and
// lowering into the Model) against a bare urdfdom parse of the same text, the floor any importer
// pays. Medians of R repetitions, in turn; see bench/README.md ("URDF").
//
// Usage: build/bench/urdf_bench [-r 21] FILE.urdf...
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/registry.h"

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 21;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-r") == 0 && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else
      files.emplace_back(argv[i]);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: urdf_bench [-r REPS] FILE.urdf...\n");
    return 64;
  }
  simbob::Registry reg;
  simbob::registerBuiltins(reg);
  std::printf("%-28s %12s %12s %8s %7s %7s\n", "file", "urdfdom ms", "simbob ms", "ratio", "bodies", "meshes");
  for (const std::string& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::vector<double> bare, full;
    size_t bodies = 0, meshes = 0;
    for (int r = 0; r < reps; ++r) {
      double t = now();
      urdf::ModelInterfaceSharedPtr m = urdf::parseURDF(text);
      bare.push_back(now() - t);
      if (!m) {
        std::fprintf(stderr, "urdf_bench: urdfdom refuses %s\n", f.c_str());
        return 65;
      }
      t = now();
      simbob::Scene scene;
      simbob::Model model;
      simbob::Diagnostics d;
      const bool ok = simbob::loadScene(f, reg, &scene, d) && simbob::compileScene(scene, &model, d);
      full.push_back(now() - t);
      if (!ok) {
        std::fprintf(stderr, "urdf_bench: %s\n", d.errors().empty() ? "?" : d.errors()[0].str().c_str());
        return 65;
      }
      bodies = model.bodies.size();
      meshes = scene.files.size() - 1;
    }
    const double b = median(bare) * 1e3, s = median(full) * 1e3;
    const std::string name = f.substr(f.find_last_of('/') + 1);
    std::printf("%-28s %12.3f %12.3f %8.1f %7zu %7zu\n", name.c_str(), b, s, s / b, bodies, meshes);
  }
  return 0;
}
