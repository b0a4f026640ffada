// chain_bench: the cost of a step of a long hinged chain in bare ODE (issue 42, point 7;
// docs/performance.md, "Long chains"). It links ODE only, none of simbob.
//
// Usage: chain_bench [--contacts] [--steps S] N...
//
// For each N: a chain of N links (0.1 m x 0.02 m x 0.02 m boxes, 0.1 kg), each hinged about Y to
// the one before at its end, the first to the world -- the bodies and joints in the order
// simbob creates a URDF chain's -- with ERP 0.2, CFM 1e-10 and 20 QuickStep iterations as
// simbob sets them. Without --contacts the chain hangs 1000 m up (joints only); with it, it lies
// 5 cm above a ground plane, falls onto it in 0.1 s and rests there (up to 4 contacts per link, as
// simbob's MaxContacts). After 150 settling steps it takes S more (default 50) and prints one JSON
// line per N: the median thread CPU time of a step (ms, clock_gettime CLOCK_THREAD_CPUTIME_ID),
// the rows QuickStep solved in the last step and the median time per row and iteration (ns).
#include <ode/ode.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

namespace {

struct Chain {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contacts = nullptr;
  std::vector<dBodyID> bodies;
  int contactRows = 0;
};

void nearCallback(void* data, dGeomID g1, dGeomID g2) {
  auto& c = *static_cast<Chain*>(data);
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (b1 == b2) return;
  if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
  dContact buf[4];
  const int n = dCollide(g1, g2, 4, &buf[0].geom, sizeof(dContact));
  for (int k = 0; k < n; ++k) {
    buf[k].surface.mode = dContactBounce | dContactApprox1;
    buf[k].surface.mu = 1;
    buf[k].surface.bounce = 0;
    buf[k].surface.bounce_vel = 0.01;
    dJointID j = dJointCreateContact(c.world, c.contacts, &buf[k]);
    dJointAttach(j, b1, b2);
    c.contactRows += 3;
  }
}

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  bool withContacts = false;
  int steps = 50;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--contacts") == 0) {
      withContacts = true;
    } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
      steps = std::atoi(argv[++i]);
    } else {
      sizes.push_back(std::atoi(argv[i]));
    }
  }
  if (sizes.empty() || steps < 1) {
    std::fprintf(stderr, "usage: chain_bench [--contacts] [--steps S] N...\n");
    return 2;
  }
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  for (int n : sizes) {
    Chain c;
    dRandSetSeed(0);
    c.world = dWorldCreate();
    dWorldSetGravity(c.world, 0, 0, -9.81);
    dWorldSetERP(c.world, 0.2);
    dWorldSetCFM(c.world, 1e-10);
    dWorldSetQuickStepNumIterations(c.world, 20);
    c.space = dHashSpaceCreate(nullptr);
    c.contacts = dJointGroupCreate(0);
    const double z = withContacts ? 0.05 : 1000;
    if (withContacts) dCreatePlane(c.space, 0, 0, 1, 0);
    for (int i = 0; i < n; ++i) {
      dBodyID b = dBodyCreate(c.world);
      dMass m;
      dMassSetParameters(&m, 0.1, 0, 0, 0, 1e-4, 1e-4, 1e-4, 0, 0, 0);
      dBodySetMass(b, &m);
      dBodySetPosition(b, 0.1 * i + 0.05, 0, z);
      dGeomID g = dCreateBox(c.space, 0.1, 0.02, 0.02);
      dGeomSetBody(g, b);
      c.bodies.push_back(b);
    }
    for (int i = 0; i < n; ++i) {
      dJointID j = dJointCreateHinge(c.world, nullptr);
      dJointAttach(j, i == 0 ? nullptr : c.bodies[static_cast<size_t>(i - 1)], c.bodies[static_cast<size_t>(i)]);
      dJointSetHingeAnchor(j, 0.1 * i, 0, z);
      dJointSetHingeAxis(j, 0, 1, 0);
    }
    std::vector<double> times;
    for (int s = 0; s < 150 + steps; ++s) {
      const double t0 = threadSeconds();
      c.contactRows = 0;
      dSpaceCollide(c.space, &c, &nearCallback);
      dWorldQuickStep(c.world, 0.001);
      dJointGroupEmpty(c.contacts);
      if (s >= 150) times.push_back(threadSeconds() - t0);
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    const int rows = 5 * n + c.contactRows;
    std::printf("{\"links\": %d, \"contacts\": %s, \"step_ms\": %.3f, \"rows\": %d, \"ns_per_row_iteration\": %.2f}\n",
                n, withContacts ? "true" : "false", median * 1e3, rows, median * 1e9 / (rows * 20.0));
    std::fflush(stdout);
    dJointGroupDestroy(c.contacts);
    dSpaceDestroy(c.space);
    dWorldDestroy(c.world);
  }
  dCloseODE();
  return 0;
}
