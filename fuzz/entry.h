// What each fuzz target does with one input, shared by the libFuzzer mains in fuzz/*_fuzzer.cpp
// and by the regression test tests/fuzz/fuzz_regression_test.cpp (which feeds every file under
// tests/data/fuzz/<target>/ through the same function). Header-only so that the normal test
// target needs no extra source file.
//
// Each entry returns "" when the input was handled correctly (accepted or rejected with a
// message) and a description of the broken invariant otherwise. Crashes, sanitizer reports,
// hangs and runaway allocations are caught by the fuzzer / test harness itself.
#pragma once

#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <variant>
#include <vector>

#include "physics/parallel_test_hooks.h"
#include "simbob/tool/comparison.h"
#include "simbob/compile.h"
#include "simbob/graph.h"
#include "simbob/mesh.h"
#include "simbob/registry.h"
#include "simbob/scene_run.h"
#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob::fuzz {

/// The built-in types, registered once per fuzzing process.
inline const Registry& fuzzRegistry() {
  static const Registry reg = [] {
    Registry r;
    registerBuiltins(r);
    return r;
  }();
  return reg;
}

/// The fuzz targets; the names are the directories under fuzz/corpus/ and tests/data/fuzz/.
inline const std::vector<std::string>& targetNames() {
  static const std::vector<std::string> names{"scene_xml",  "scene_ini", "scene_run", "values",
                                              "trajectory", "mesh",      "urdf"};
  return names;
}

/// A fresh, empty directory private to this process, removed at exit. Scenes are "loaded" from
/// a name inside it, so relative imports find nothing and fail cleanly; trajectories are
/// written into it to be read back.
class TempDir {
 public:
  static const std::string& path() {
    static TempDir dir;
    return dir.path_;
  }

  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

 private:
  TempDir() {
    std::error_code ec;
    std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string templ = (base / "simbob-fuzz-XXXXXX").string();
    std::vector<char> buf(templ.begin(), templ.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data())) {
      std::perror("simbob fuzz: mkdtemp");
      std::abort();
    }
    path_ = buf.data();
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string path_;
};

// ------------------------------------------------------------------------------------ scenes

inline std::string sceneName(Format format) {
  return TempDir::path() + (format == Format::Xml ? "/scene.xml" : "/scene.ini");
}

/// loadSceneFromText; if it loads, compileScene and writeScene in both formats (with and
/// without defaults). What the writer writes must load again and be written the same way
/// (graph.h: the writers' output is a scene file).
inline std::string runScene(const uint8_t* data, size_t size, Format format) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string name = sceneName(format);
  Scene scene;
  Diagnostics diag;
  if (!loadSceneFromText(text, name, format, fuzzRegistry(), &scene, diag)) {
    if (diag.errors().empty()) return "loadSceneFromText failed without an error message";
    return {};
  }
  if (!diag.errors().empty()) return "loadSceneFromText succeeded but reported errors";
  Model model;
  Diagnostics cdiag;
  bool compiled = compileScene(scene, &model, cdiag);
  if (!compiled && cdiag.errors().empty()) return "compileScene failed without an error message";
  for (Format f : {Format::Xml, Format::Ini}) {
    for (bool fill : {false, true}) {
      const std::string what =
          std::string("writeScene(") + (f == Format::Xml ? "Xml" : "Ini") + (fill ? ", defaults" : "") + ")";
      const std::string out = writeScene(scene, f, fill);
      if (out.empty() && (f == Format::Xml || fill)) return what + " wrote nothing for a loaded scene";
      Scene again;
      Diagnostics adiag;
      if (!loadSceneFromText(out, sceneName(f), f, fuzzRegistry(), &again, adiag))
        return what + " wrote a scene that does not load: " +
               (adiag.errors().empty() ? std::string("(no message)") : adiag.errors().front().str());
      if (writeScene(again, f, fill) != out) return what + " of the reloaded scene differs";
    }
  }
  return {};
}

inline std::string runSceneXml(const uint8_t* data, size_t size) { return runScene(data, size, Format::Xml); }
inline std::string runSceneIni(const uint8_t* data, size_t size) { return runScene(data, size, Format::Ini); }

/// Steps of kRunStep a scene that loads and compiles is run for (scene_run).
constexpr int kRunSteps = 20;
constexpr double kRunStep = 0.001;

/// Every body's state and every sensor's reading when a run completes, as bits.
class FinalState : public Party {
 public:
  SimTime first() override { return kNever; }
  SimTime onGrant(SimTime, World&) override { return kNever; }
  void finish(SimTime, World& world) override {
    for (int b = 0; b < world.bodyCount(); ++b) {
      const BodyState s = world.body(b);
      values.insert(values.end(), s.pose.p.begin(), s.pose.p.end());
      values.insert(values.end(), s.pose.q.begin(), s.pose.q.end());
      values.insert(values.end(), s.lin_vel.begin(), s.lin_vel.end());
      values.insert(values.end(), s.ang_vel.begin(), s.ang_vel.end());
    }
    for (int i = 0; i < world.sensorCount(); ++i) {
      const std::vector<double>& r = world.sensorReading(i);
      values.insert(values.end(), r.begin(), r.end());
    }
  }
  std::vector<double> values;
};

/// How one run of scene_run ended.
struct RunEnd {
  bool opened = false;
  RunStatus status = RunStatus::Failed;
  uint64_t steps = 0;
  std::string message;        ///< the refusal's or the run's error ("" for a completed run)
  std::vector<double> state;  ///< FinalState's values (a completed run)
};

inline RunEnd runSteps(const std::string& text, int threads) {
  RunOptions o;
  o.scene = sceneName(Format::Xml);
  o.scene_text = text;
  o.write_outputs = false;
  o.warnings = false;
  o.simulation.dt = kRunStep;
  o.simulation.duration = kRunSteps * kRunStep;
  o.simulation.threads = threads;
  o.simulation.no_controllers = true;
  o.simulation.peer_timeout = 0.001;
  RunEnd end;
  Error refusal;
  std::unique_ptr<Run> run = Run::open(o, fuzzRegistry(), RunListener{}, &refusal);
  if (!run) {
    end.message = refusal.message;
    return end;
  }
  end.opened = true;
  FinalState final_state;
  run->simulation().addParty(final_state);
  const RunResult& r = run->finish().result;
  end.status = r.status;
  end.steps = r.steps;
  end.message = r.error.message;
  end.state = std::move(final_state.values);
  return end;
}

/// An XML scene run through a Run, as every client runs one (simbob/scene_run.h), for kRunSteps
/// steps of kRunStep s, on one thread and again on three: it writes nothing and starts no
/// program (no_controllers), and a socket peer it waits for gives up at once. What the scene asks
/// of ODE (joints, drives, sensors, contacts) must end in a completed run of every step, or in a
/// run that stopped, or was refused, with a message; never in a crash, a sanitizer report or a
/// hang. And the thread count changes nothing: the same end, every state and reading the same
/// bits (World::create).
inline std::string runSceneSteps(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const RunEnd one = runSteps(text, 1);
  if (!one.opened) return one.message.empty() ? "Run::open refused the scene without a message" : std::string();
  if (one.status != RunStatus::Completed && one.message.empty()) return "a run that did not complete says nothing";
  if (one.status == RunStatus::Completed && one.steps != static_cast<uint64_t>(kRunSteps))
    return "a completed run took " + std::to_string(one.steps) + " steps, not " + std::to_string(kRunSteps);
  // Every pair and swept box a chunk of its own: without it a scene of fewer than 256 pairs
  // collides on the stepping thread alone (kPairGrain), and the comparison would test little.
  const size_t grain = parallelTestHooks().grain;
  parallelTestHooks().grain = 1;
  const RunEnd three = runSteps(text, 3);
  parallelTestHooks().grain = grain;
  // The messages are not compared: one about a socket peer may name wall-clock times.
  if (!three.opened || three.status != one.status || three.steps != one.steps)
    return "on 3 threads the run ends otherwise (" + std::to_string(three.steps) + " steps: " + three.message +
           ") than on 1 (" + std::to_string(one.steps) + " steps: " + one.message + ")";
  if (three.state.size() != one.state.size() ||
      (!one.state.empty() &&  // memcmp of an empty vector's null data is undefined
       std::memcmp(three.state.data(), one.state.data(), one.state.size() * sizeof(double)) != 0))
    return "on 3 threads the bodies and sensors end in other bits than on 1";
  return {};
}

// ------------------------------------------------------------------------------------ values

/// Enum/bitmask tables: every table of the built-in registry, plus synthetic ones covering
/// aliases, a zero key, overlapping bits and the greedy path for tables of more than 20 keys.
inline const std::vector<const EnumTable*>& fuzzTables() {
  static const EnumTable aliases{"FuzzAliases",
                                 {{"None", 0},
                                  {"Left", 1},
                                  {"MinX", 1},
                                  {"Right", 2},
                                  {"Both", 3},
                                  {"Top", 4},
                                  {"High", 0x80000000u},
                                  {"Wide", 0x0000ff00u}}};
  static const EnumTable no_zero{"FuzzNoZero", {{"A", 1}, {"B", 6}, {"C", 12}, {"D", 24}}};
  // 24 keys, each "all of the low 24 bits but one": the full mask takes the greedy path, any
  // other mask has at most one candidate key. (Tables of up to 20 single-bit keys make the
  // exhaustive search of formatBitmask try ~2^20 combinations; no built-in table comes close.)
  static const EnumTable big = [] {
    EnumTable t{"FuzzBig", {}};
    static const char* const names[] = {"K0",  "K1",  "K2",  "K3",  "K4",  "K5",  "K6",  "K7",
                                        "K8",  "K9",  "K10", "K11", "K12", "K13", "K14", "K15",
                                        "K16", "K17", "K18", "K19", "K20", "K21", "K22", "K23"};
    for (uint32_t i = 0; i < 24; ++i) t.keys.push_back({names[i], 0xFFFFFFu ^ (1u << i)});
    return t;
  }();
  static const std::vector<const EnumTable*> tables = [] {
    std::vector<const EnumTable*> v;
    std::set<const EnumTable*> seen;
    for (const TypeSpec& t : fuzzRegistry().types())
      for (const ParamSpec& p : t.params)
        if (p.table && seen.insert(p.table).second) v.push_back(p.table);
    v.push_back(&aliases);
    v.push_back(&no_zero);
    v.push_back(&big);
    return v;
  }();
  return tables;
}

/// Bit-for-bit equality of two values (values.h: parse(write(v)) == v bit for bit), so that
/// -0 and +0 differ; an invalid Color equals any invalid Color.
inline bool sameBits(const Value& a, const Value& b) {
  if (a.index() != b.index()) return false;
  auto bits = [](const double* x, const double* y, size_t n) { return std::memcmp(x, y, n * sizeof(double)) == 0; };
  if (auto* x = std::get_if<double>(&a)) return bits(x, std::get_if<double>(&b), 1);
  if (auto* x = std::get_if<Triple>(&a)) return bits(x->data(), std::get_if<Triple>(&b)->data(), 3);
  if (auto* x = std::get_if<Vector4>(&a)) return bits(x->v.data(), std::get_if<Vector4>(&b)->v.data(), 4);
  if (auto* x = std::get_if<Quaternion>(&a)) return bits(x->q.data(), std::get_if<Quaternion>(&b)->q.data(), 4);
  if (auto* x = std::get_if<Pose>(&a)) {
    auto* y = std::get_if<Pose>(&b);
    return bits(x->pos.data(), y->pos.data(), 3) && bits(x->euler_deg.data(), y->euler_deg.data(), 3);
  }
  if (auto* x = std::get_if<Matrix4>(&a)) return bits(x->m.data(), std::get_if<Matrix4>(&b)->m.data(), 16);
  if (auto* x = std::get_if<Cuboid>(&a)) {
    auto* y = std::get_if<Cuboid>(&b);
    return bits(x->a.data(), y->a.data(), 3) && bits(x->b.data(), y->b.data(), 3);
  }
  if (auto* x = std::get_if<Color>(&a)) {
    auto* y = std::get_if<Color>(&b);
    return x->valid == y->valid && (!x->valid || bits(x->rgba.data(), y->rgba.data(), 4));
  }
  return a == b;  // bool, int64, string, enum, bitmask
}

/// One value type: parse `text`; when it parses, write it and parse the result again. The
/// second parse must succeed and give the same value bit for bit. Vectors are written
/// normalised (x/w, y/w, z/w, 1) by design, so for them the written text must be a fixed point
/// (write(parse(write(v))) == write(v)) and the value must come back exactly when w is 1.
inline std::string checkValue(ValueType t, std::string_view text, const EnumTable* table, ParseOptions opts) {
  ParseResult r = parseValue(t, text, table, opts);
  if (!r) {
    if (r.error.empty()) return std::string(valueTypeName(t)) + ": parse failed without a message";
    return {};
  }
  const std::string written = formatValue(t, *r.value, table);
  const std::string what = std::string(valueTypeName(t)) + (table ? std::string(" (") + table->name + ")" : "") +
                           (opts.allow_infinite ? " [allow_infinite]" : "") + ": '" + std::string(text) +
                           "' was written as '" + written + "'";
  ParseResult back = parseValue(t, written, table, opts);
  if (!back) return what + ", which does not parse: " + back.error;
  if (t == ValueType::Vector) {
    const std::string again = formatValue(t, *back.value, table);
    if (again != written) return what + ", which reads back and is written as '" + again + "'";
    if (std::get<Vector4>(*r.value).v[3] == 1.0 && !sameBits(*r.value, *back.value))
      return what + ", which reads back as a different value";
    return {};
  }
  if (!sameBits(*r.value, *back.value)) return what + ", which reads back as a different value";
  return {};
}

/// parseValue for every value type (numbers and lists with and without allow_infinite, Enum
/// and Bitmask with a table), and the write/read round trip of every value that parses.
inline std::string runValues(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const ValueType kTypes[] = {ValueType::Bool,   ValueType::Int,    ValueType::Number,     ValueType::String,
                                     ValueType::Triple, ValueType::Vector, ValueType::Quaternion, ValueType::Pose,
                                     ValueType::Matrix, ValueType::Cuboid, ValueType::Color};
  for (bool inf : {false, true}) {
    ParseOptions opts;
    opts.allow_infinite = inf;
    for (ValueType t : kTypes) {
      std::string problem = checkValue(t, text, nullptr, opts);
      if (!problem.empty()) return problem;
    }
  }
  // Enum and Bitmask with one table, picked by a hash of the input: every table is reached
  // while each run stays cheap (a failed key lookup computes edit distances for its message).
  // allow_infinite does not apply to keys.
  uint32_t h = 2166136261u;
  for (unsigned char c : text) h = (h ^ c) * 16777619u;
  const EnumTable* table = fuzzTables()[h % fuzzTables().size()];
  for (ValueType t : {ValueType::Enum, ValueType::Bitmask}) {
    std::string problem = checkValue(t, text, table, ParseOptions{});
    if (!problem.empty()) return problem;
  }
  // Without a table Enum/Bitmask must fail cleanly, never crash.
  for (ValueType t : {ValueType::Enum, ValueType::Bitmask})
    if (parseValue(t, text, nullptr)) return std::string(valueTypeName(t)) + " parsed without a key table";
  return {};
}

// ------------------------------------------------------------------------------------ trajectories

/// Writes the input to a file of this process, reads it with readTrajectory and, if it reads,
/// compares the trajectory with itself: that must find no structural mismatch and compare
/// every row that is present.
inline std::string runTrajectory(const uint8_t* data, size_t size) {
  const std::string path = TempDir::path() + "/trajectory.csv";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) {
      std::perror(("simbob fuzz: " + path).c_str());
      std::abort();
    }
    if (size && std::fwrite(data, 1, size, f) != size) {
      std::perror(("simbob fuzz: " + path).c_str());
      std::abort();
    }
    std::fclose(f);
  }
  Trajectory t;
  Error err;
  if (!readTrajectory(path, &t, &err)) {
    if (err.message.empty()) return "readTrajectory failed without an error message";
    return {};
  }
  // Shape invariants of trajectory.h.
  if (t.poses.size() != t.bodies.size() || t.present.size() != t.bodies.size())
    return "per-body columns do not match the body count";
  for (size_t s = 1; s < t.times.size(); ++s)
    if (!(t.times[s - 1] < t.times[s])) return "sample times are not increasing";
  size_t rows = 0;
  for (size_t b = 0; b < t.bodies.size(); ++b) {
    if (t.present[b].size() != t.times.size() || t.poses[b].size() != t.times.size() * kPoseSize)
      return "column of body '" + t.bodies[b] + "' is not sized to the sample count";
    for (size_t s = 0; s < t.times.size(); ++s) rows += t.present[b][s] ? 1 : 0;
  }
  // Storage is dense (bodies x sample times); readTrajectory keeps it linear in the row count
  // (lib/output/trajectory.cpp: at most 16 cells per row beyond 2^20 cells).
  const size_t cells = t.bodies.size() * t.times.size();
  if (cells > (size_t{1} << 20) && cells / 16 > rows)
    return "dense storage of " + std::to_string(cells) + " cells for " + std::to_string(rows) + " rows";
  CompareResult r = compareTrajectories(t, t);
  if (r.structuralMismatch()) return "a trajectory compared with itself shows a structural mismatch";
  if (r.shared_samples != t.times.size() || r.bodies.size() != t.bodies.size())
    return "a trajectory compared with itself does not share every sample and body";
  size_t compared = 0;
  for (const BodyDiff& d : r.bodies) compared += d.compared;
  if (compared != rows) return "a trajectory compared with itself does not compare every row";
  (void)r.text();
  (void)r.json().dump();
  return {};
}

/// The entry for a target name, or nullptr.
using Entry = std::string (*)(const uint8_t*, size_t);
// ------------------------------------------------------------------------------------ meshes

/// A folder of this process's own for the files the file-reading targets write (the mesh reader
/// reads a path, as a scene's RCMeshGeom names one).
inline const std::filesystem::path& scratchFolder() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("simbob-fuzz-" + std::to_string(static_cast<long>(getpid())));
    std::error_code ec;
    std::filesystem::create_directories(d, ec);
    return d;
  }();
  return dir;
}

inline bool writeScratch(const std::filesystem::path& p, const uint8_t* data, size_t size) {
  std::FILE* f = std::fopen(p.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok;
}

/// Mesh files (lib/mesh: the byte scan, then assimp, then qhull). The first byte picks the
/// extension (.stl, .obj, .dae) and the frame (scene Y-up or URDF Z-up); the rest is the file.
/// Loaded or refused with a message, never a crash, hang or runaway allocation; what loads keeps
/// the documented limits: at least one triangle, indices in range, vertices finite and within
/// kMaxMeshCoordinate, counts within kMaxMeshVertices and kMaxMeshTriangles, bounds that hold
/// every vertex, and a hull or a reason for none.
inline std::string runMesh(const uint8_t* data, size_t size) {
  if (size == 0) return {};
  static const char* const kExt[] = {".stl", ".obj", ".dae"};
  const std::filesystem::path file = scratchFolder() / (std::string("mesh") + kExt[data[0] % 3]);
  const UpAxis up = (data[0] / 3) % 2 ? UpAxis::Z : UpAxis::Y;
  if (!writeScratch(file, data + 1, size - 1)) return {};  // the machine's disk, not the reader
  const MeshLoad load = loadMesh(file.string(), Vec3{1, 1, 1}, up);
  if (!load.ok()) {
    if (load.error.message.empty()) return "loadMesh refused a file without a message";
    if (load.error.kind != ErrorKind::InvalidInput)
      return "loadMesh refused a regular file with a kind other than InvalidInput: " + load.error.message;
    return {};
  }
  const MeshData& m = *load.mesh;
  if (m.triangles.empty()) return "a loaded mesh has no triangle";
  if (m.vertices.size() > kMaxMeshVertices || m.triangles.size() > kMaxMeshTriangles)
    return "a loaded mesh is over the limits: " + std::to_string(m.vertices.size()) + " vertices, " +
           std::to_string(m.triangles.size()) + " triangles";
  for (const auto& t : m.triangles)
    for (uint32_t i : t)
      if (i >= m.vertices.size())
        return "a triangle names vertex " + std::to_string(i) + " of " + std::to_string(m.vertices.size());
  for (const Vec3& v : m.vertices)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(v[k]) || std::fabs(v[k]) > kMaxMeshCoordinate) return "a vertex beyond the limit was loaded";
      if (v[k] < m.lo[k] || v[k] > m.hi[k]) return "a vertex lies outside the mesh's bounds";
    }
  if (m.hull.empty() == m.hull_problem.empty()) return "a hull and its problem disagree";
  return {};
}

// -------------------------------------------------------------------------------------- URDF

/// URDF files (lib/urdf): read as `simbob check robot.urdf` reads one, bare, over the ground.
/// Loaded and compiled, or refused with file:line, never a crash or a hang; a robot that loads
/// compiles to a model whose bodies are all finite.
inline std::string runUrdf(const uint8_t* data, size_t size) {
  const std::filesystem::path file = scratchFolder() / "robot.urdf";
  if (!writeScratch(file, data, size)) return {};
  Model model;
  LoadRequest request;
  request.path = file.string();
  request.lint = true;  // as `simbob check` does: the checks run on what loaded
  LoadReport report;
  const bool ok = loadModel(request, fuzzRegistry(), &model, &report);
  const Diagnostics& diag = report.diagnostics;
  if (!ok) {
    if (diag.errors().empty()) return "a URDF was refused without a message";
    for (const Error& e : diag.errors())
      if (e.kind == ErrorKind::Internal) return "a URDF met an internal error: " + e.message;
    return {};
  }
  if (!diag.errors().empty()) return "a URDF loaded but reported errors";
  for (const BodyDef& b : model.bodies)
    for (double v : b.pose.p)
      if (!std::isfinite(v)) return "a URDF body starts at a non-finite place";
  return {};
}

inline Entry entryFor(std::string_view target) {
  if (target == "scene_xml") return runSceneXml;
  if (target == "scene_ini") return runSceneIni;
  if (target == "scene_run") return runSceneSteps;
  if (target == "values") return runValues;
  if (target == "trajectory") return runTrajectory;
  if (target == "mesh") return runMesh;
  if (target == "urdf") return runUrdf;
  return nullptr;
}

/// For the libFuzzer mains: run the entry and abort (a finding) when an invariant broke.
inline int fuzzOne(Entry entry, const uint8_t* data, size_t size) {
  std::string problem = entry(data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "simbob fuzz: invariant broken: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}

}  // namespace simbob::fuzz
