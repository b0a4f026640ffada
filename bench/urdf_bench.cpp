// Load time of URDF robots (issue 28): simbob's whole load of a robot.urdf (read by simbob's
// reader on pugixml, package:// paths, meshes read and hulled, planning and lowering into the
// Model) against a bare pugixml parse of the same text, the floor any importer pays. Process CPU time (a shared machine's load moves it less than wall time),
// medians of R repetitions, in turn; see bench/README.md ("URDF").
//
// Usage: build/bench/urdf_bench [-r 21] [--pose "x y z a b c"] FILE.urdf...
//   --pose: load the files that follow through an RCImportURDF with that Pose in a one-robot
//   scene (dart-doc's KR5, which lies in the ground as a bare robot, stood up) instead of bare.
#include <pugixml.hpp>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/mesh.h"
#include "simbob/registry.h"

namespace {

double now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 21;
  std::vector<std::pair<std::string, std::string>> files;  // file, pose ("" bare)
  std::string pose;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-r") == 0 && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--pose") == 0 && i + 1 < argc)
      pose = argv[++i];
    else
      files.emplace_back(argv[i], pose);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: urdf_bench [-r REPS] FILE.urdf...\n");
    return 64;
  }
  simbob::Registry reg;
  simbob::registerBuiltins(reg);
  // meshes ms: simbob::loadMesh alone (assimp's read, units and axes, qhull's hull, masses) for
  // each mesh the loaded model holds; "rest" is the load without it, against the bare parse.
  std::printf("%-24s %10s %10s %7s %10s %10s %7s %6s %6s\n", "file", "xml ms", "simbob ms", "ratio", "meshes ms",
              "rest ms", "ratio", "bodies", "meshes");
  for (const auto& [f, at] : files) {
    const std::string dir = f.substr(0, f.find_last_of('/') + 1);
    const std::string scene_text =
        "<Simulation><ComponentList><RCGround Key=\"Ground\"/><RCImportURDF Key=\"robot\"><File Value=\"" +
        f.substr(dir.size()) + "\"/><Pose><RCGlobalCoordinates><Pose Value=\"" + at +
        "\"/></RCGlobalCoordinates></Pose></RCImportURDF></ComponentList></Simulation>";
    std::ifstream in(f, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::vector<double> bare, full, mesh;
    size_t bodies = 0, meshes = 0;
    for (int r = 0; r < reps; ++r) {
      double t = now();
      pugi::xml_document doc;
      const bool parsed = static_cast<bool>(doc.load_buffer(text.data(), text.size()));
      bare.push_back(now() - t);
      if (!parsed) {
        std::fprintf(stderr, "urdf_bench: pugixml refuses %s\n", f.c_str());
        return 65;
      }
      t = now();
      simbob::Scene scene;
      simbob::Model model;
      simbob::Diagnostics d;
      const bool ok = (at.empty() ? simbob::loadScene(f, reg, &scene, d)
                                  : simbob::loadSceneFromText(scene_text, dir + "urdf_bench.xml", simbob::Format::Xml,
                                                              reg, &scene, d)) &&
                      simbob::compileScene(scene, &model, d);
      full.push_back(now() - t);
      if (!ok) {
        std::fprintf(stderr, "urdf_bench: %s\n", d.errors().empty() ? "?" : d.errors()[0].str().c_str());
        return 65;
      }
      bodies = model.bodies.size();
      meshes = model.meshes.size();
      t = now();
      for (const auto& m : model.meshes) {
        const simbob::MeshLoad again = simbob::loadMesh(m.data->file, m.data->scale, m.data->up);
        if (!again.ok()) return 70;
      }
      mesh.push_back(now() - t);
    }
    const double b = median(bare) * 1e3, s = median(full) * 1e3, m = median(mesh) * 1e3;
    const std::string name = f.substr(f.find_last_of('/') + 1);
    std::printf("%-24s %10.3f %10.3f %7.1f %10.3f %10.3f %7.1f %6zu %6zu\n", name.c_str(), b, s, s / b, m, s - m,
                (s - m) / b, bodies, meshes);
  }
  return 0;
}
