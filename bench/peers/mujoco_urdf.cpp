// MuJoCo's side of bench/peers (issue 42): MuJoCo 2.2.2 (Debian's libmujoco-dev) reads a URDF
// itself (mj_loadXML), steps it at 1 ms and prints, as one JSON line, the process CPU time of
// the load (model and data, median of the loads) and of the steps alone, with the joint angles
// at the end. Built by bench/CMakeLists.txt only where libmujoco is found; run by
// bench/peers/run.py, which writes the URDFs and compares with simbob (bench/README.md, "Peers").
//
// Usage: mujoco_urdf FILE.urdf STEPS [--loads K] [--floor] [--smooth S] [--maxforce F]
//                    [--gain G] [--drive JOINT VMAX]... [--command JOINT TIME TARGET]...
//   --floor        step the model with a ground plane at z = 0, as simbob's runs have one, and
//                  without self-collision (simbob's default, SelfCollision false): after the
//                  timed loads the URDF's model is saved as MJCF (mj_saveLastXML), a plane is
//                  added to its worldbody and it is loaded again; every geom but the plane gets
//                  conaffinity 0, so the robot's geoms meet the plane and not each other
//   --drive        a position drive on JOINT with simbob's law (docs/urdf.md, "Drives"): wanted
//                  velocity v = clamp((target - q) / S, +-VMAX), torque clamp(kv (v - qdot), +-F)
//                  into qfrc_applied before each step, kv = G * M0 / h (M0 the joint's diagonal
//                  inertia at qpos0, h the step); target 0 until a --command at TIME (s) sets it.
//                  ODE's motor reaches v within F in one step as a constraint; MuJoCo has no
//                  such motor, so this is the nearest force law (G 0.2: a fifth of the velocity
//                  error per step, stable with explicit damping).
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

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

struct Drive {
  std::string joint;
  double vmax = 0;
  int dof = -1, qadr = -1;
  double kv = 0, target = 0;
};

struct Command {
  std::string joint;
  double time = 0, target = 0;
  bool done = false;
};

// The loaded URDF's model again from MJCF with a plane at z = 0 (see --floor).
bool addFloor(mjModel** m, mjData** d) {
  char path[] = "/tmp/simbob-peers-XXXXXX.xml";
  const int fd = mkstemps(path, 4);
  if (fd < 0) return false;
  close(fd);
  char err[1000] = "";
  if (!mj_saveLastXML(path, *m, err, sizeof err)) {
    std::fprintf(stderr, "mujoco_urdf: mj_saveLastXML: %s\n", err);
    return false;
  }
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string xml = ss.str();
  const size_t at = xml.find("<worldbody>");
  if (at == std::string::npos) return false;
  xml.insert(at + 11, "\n    <geom name=\"simbob_peers_floor\" type=\"plane\" size=\"0 0 1\"/>");
  std::ofstream(path) << xml;
  mj_deleteData(*d);
  mj_deleteModel(*m);
  *m = mj_loadXML(path, nullptr, err, sizeof err);
  std::remove(path);
  if (!*m) {
    std::fprintf(stderr, "mujoco_urdf: the model with a floor: %s\n", err);
    return false;
  }
  // Only the plane has conaffinity: a pair collides when one's contype meets the other's
  // conaffinity, so the robot's geoms meet the plane and never each other -- nor the geoms of a
  // base fused into the world body, which MuJoCo would otherwise test against its child link.
  const int plane = mj_name2id(*m, mjOBJ_GEOM, "simbob_peers_floor");
  for (int g = 0; g < (*m)->ngeom; ++g) {
    (*m)->geom_contype[g] = 1;
    (*m)->geom_conaffinity[g] = g == plane ? 1 : 0;
  }
  *d = mj_makeData(*m);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: mujoco_urdf FILE.urdf STEPS [--loads K] [--floor] [--smooth S] [--maxforce F] "
                 "[--gain G] [--drive JOINT VMAX]... [--command JOINT TIME TARGET]...\n");
    return 64;
  }
  const char* file = argv[1];
  const long steps = std::atol(argv[2]);
  int loads = 5;
  bool floor = false;
  double smooth = 0.05, maxforce = 500, gain = 0.2;
  std::vector<Drive> drives;
  std::vector<Command> commands;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--loads" && i + 1 < argc) {
      loads = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--floor") {
      floor = true;
    } else if (a == "--smooth" && i + 1 < argc) {
      smooth = std::atof(argv[++i]);
    } else if (a == "--maxforce" && i + 1 < argc) {
      maxforce = std::atof(argv[++i]);
    } else if (a == "--gain" && i + 1 < argc) {
      gain = std::atof(argv[++i]);
    } else if (a == "--drive" && i + 2 < argc) {
      Drive d;
      d.joint = argv[i + 1];
      d.vmax = std::atof(argv[i + 2]);
      drives.push_back(d);
      i += 2;
    } else if (a == "--command" && i + 3 < argc) {
      commands.push_back({argv[i + 1], std::atof(argv[i + 2]), std::atof(argv[i + 3])});
      i += 3;
    } else {
      std::fprintf(stderr, "mujoco_urdf: unknown argument '%s'\n", a.c_str());
      return 64;
    }
  }

  std::vector<double> load_cpu, load_wall;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  char err[1000] = "";
  for (int k = 0; k < loads; ++k) {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
    const double c0 = cpuNow(), w0 = wallNow();
    m = mj_loadXML(file, nullptr, err, sizeof err);
    if (!m) {
      std::fprintf(stderr, "mujoco_urdf: %s: %s\n", file, err);
      return 65;
    }
    d = mj_makeData(m);
    load_cpu.push_back(cpuNow() - c0);
    load_wall.push_back(wallNow() - w0);
  }
  if (floor && !addFloor(&m, &d)) return 70;
  m->opt.timestep = 0.001;
  for (Drive& dr : drives) {
    const int j = mj_name2id(m, mjOBJ_JOINT, dr.joint.c_str());
    if (j < 0) {
      std::fprintf(stderr, "mujoco_urdf: %s has no joint '%s'\n", file, dr.joint.c_str());
      return 65;
    }
    dr.dof = m->jnt_dofadr[j];
    dr.qadr = m->jnt_qposadr[j];
    dr.kv = gain * m->dof_M0[dr.dof] / m->opt.timestep;
  }
  for (const Command& c : commands) {
    if (std::none_of(drives.begin(), drives.end(), [&](const Drive& dr) { return dr.joint == c.joint; })) {
      std::fprintf(stderr, "mujoco_urdf: --command names '%s', which has no --drive\n", c.joint.c_str());
      return 64;
    }
  }

  long contacts = 0;
  const double c0 = cpuNow(), w0 = wallNow();
  for (long s = 0; s < steps; ++s) {
    if (!drives.empty()) {
      for (Command& c : commands) {
        if (!c.done && d->time >= c.time - 0.5 * m->opt.timestep) {
          for (Drive& dr : drives)
            if (dr.joint == c.joint) dr.target = c.target;
          c.done = true;
        }
      }
      for (const Drive& dr : drives) {
        const double v = std::clamp((dr.target - d->qpos[dr.qadr]) / smooth, -dr.vmax, dr.vmax);
        d->qfrc_applied[dr.dof] = std::clamp(dr.kv * (v - d->qvel[dr.dof]), -maxforce, maxforce);
      }
    }
    mj_step(m, d);
    contacts += d->ncon;
  }
  const double step_cpu = cpuNow() - c0, step_wall = wallNow() - w0;

  bool finite = true;
  for (int i = 0; i < m->nq; ++i) finite = finite && std::isfinite(d->qpos[i]);
  std::printf(
      "{\"engine\": \"mujoco\", \"version\": %d, \"file\": \"%s\", \"nbody\": %d, \"njnt\": %d, \"ngeom\": %d, "
      "\"load_cpu_s\": %.6g, \"load_first_cpu_s\": %.6g, \"load_wall_s\": %.6g, \"steps\": %ld, \"step_cpu_s\": %.6g, "
      "\"step_wall_s\": %.6g, \"contacts\": %ld, \"unstable\": %d, \"time\": %.6g, \"finite\": %s, \"qpos\": {",
      mj_version(), file, m->nbody, m->njnt, m->ngeom, median(load_cpu), load_cpu.front(), median(load_wall), steps,
      step_cpu, step_wall, contacts, d->warning[mjWARN_BADQACC].number, d->time, finite ? "true" : "false");
  for (int j = 0; j < m->njnt; ++j)
    std::printf("%s\"%s\": %.6f", j ? ", " : "", mj_id2name(m, mjOBJ_JOINT, j), d->qpos[m->jnt_qposadr[j]]);
  std::printf("}, \"solver\": \"%s\", \"iterations\": %d, \"integrator\": %d}\n",
              m->opt.solver == mjSOL_NEWTON ? "Newton" : (m->opt.solver == mjSOL_CG ? "CG" : "PGS"), m->opt.iterations,
              m->opt.integrator);
  mj_deleteData(d);
  mj_deleteModel(m);
  return finite ? 0 : 1;
}
