// World: builds an ODE world from a compiled Model and steps it. The concerns live in their own
// files (world_impl.h lists them); this file holds the world settings, the order in which the
// concerns are built, the step, and the accessors.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "simbob/values.h"
#include "world_impl.h"

namespace simbob {

namespace {

// Many Worlds in one process. ODE keeps one process-wide random generator (a 32-bit LCG in
// misc.cpp: dRand, dRandGetSeed, dRandSetSeed). In ODE 0.16 the only draw during a simulation is
// QuickStep's constraint reordering (quickstep.cpp, dRandInt every few SOR iterations); dWorldStep,
// collision (colliders, spaces, OPCODE) and object creation and destruction draw nothing (the
// other dRand callers are ODE's own self-tests). So a World owns its generator state
// (WorldImpl::rng): every call into ODE that may step runs inside an OdeSection, which sets the
// process-wide generator to the World's state on entry and takes it back on exit. A World then
// sees exactly the draws it would see alone in its process, whatever other Worlds do between its
// steps. Creation and destruction run in a section too: they draw nothing today, but the rule
// "ODE only inside a section" needs no audit when that changes. The accessors (body, joint,
// firstBadBody, ...) only read this World's own ODE objects, no ODE global, so they take none.
//
// The generator is one variable for the whole process, so two sections must never overlap:
// odeMutex() serialises them (and every other use of ODE's globals, see version.cpp). Worlds may live on different threads, but their physics does not run
// in parallel within one process (parallel worlds belong in separate processes).
std::mutex processOdeMutex;

// ODE reports through three process-wide handlers. By default it prints a message (dMessage,
// such as Solver Step's "LCP internal error, s <= 0") to stderr as a blank line and a line of
// its own, possibly every step, in the middle of simbob's output; and it ends the process on an
// error (dError: exit(1)) or a failed internal check (dDebug: abort()). Here a message goes to
// the World whose section is open (World::physicsMessages: the run reports it once), and an
// error or failed check is thrown (OdeFailure) out of ODE to the World::create or World::step
// that called it, which records it as the World's failure (ErrorKind::Internal) and never steps
// that World again: ODE's objects may be half updated. The run stops there as any failed run
// does (exit 70, its partial outputs kept); a Python interpreter gets an InternalError and goes
// on. Outside every World's section (a World being destroyed: a destructor cannot throw) it
// still ends the process with one line and status 70. The compile step refuses what ODE's checks refuse (a joint between a body and itself, a
// negative mass, numbers beyond 1e9, ...), so reaching one is a bug in simbob.
std::atomic<WorldImpl*> sectionWorld{nullptr};  // the World whose OdeSection is open, or null

constexpr int kExitInternal = 70;  // EX_SOFTWARE (README, "Exit statuses")

/// ODE's error or failed check, thrown through ODE's frames (C++, built with unwind tables) to
/// World::create or World::step.
struct OdeFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ODE's text as one line: "ODE message 3: LCP internal error, s <= 0 (s=-0.0000e+00)".
std::string odeText(const char* kind, int num, const char* msg, va_list ap) {
  char buf[512];
  std::vsnprintf(buf, sizeof buf, msg ? msg : "", ap);
  std::string text = std::string(kind) + " " + std::to_string(num) + ": " + buf;
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

void onOdeMessage(int num, const char* msg, va_list ap) {
  const std::string text = odeText("ODE message", num, msg, ap);
  WorldImpl* im = sectionWorld.load(std::memory_order_acquire);
  if (!im) {  // outside every World (none today): said at once, on one line
    std::fprintf(stderr, "simbob: warning: %s\n", text.c_str());
    return;
  }
  std::lock_guard<std::mutex> lock(im->messagesMutex);  // the narrow phase's threads may say one too
  if (im->messages.count++ == 0) {
    im->messages.first = text;
    im->messages.first_time = static_cast<double>(im->time_ns) * 1e-9;  // the step's end: World::step
    im->firstMessageInStep = true;
  }
}

[[noreturn]] void odeFatal(const char* kind, int num, const char* msg, va_list ap) {
  std::string text = odeText(kind, num, msg, ap);
  if (sectionWorld.load(std::memory_order_acquire)) throw OdeFailure(text);
  // Outside every World's section (none of simbob's calls into ODE is): nothing could catch it.
  std::fprintf(stderr,
               "simbob: error: internal error: %s (the scene reached a check in ODE that simbob should have "
               "refused before: please report it with the scene)\n",
               text.c_str());
  std::fflush(stderr);
  std::_Exit(kExitInternal);
}

// Records ODE's failure as the World's (the first failure of the World stays its failure).
void recordOdeFailure(WorldImpl& im, const OdeFailure& e, const std::string& during) {
  im.odeFailed = true;
  if (im.failure.message.empty())
    im.failure = {ErrorKind::Internal,
                  {},
                  std::string("internal error: ") + e.what() + " " + during +
                      " (the scene reached a check in ODE that simbob should have refused before: please report it "
                      "with the scene); this world is not stepped again"};
}

// Tests only (docs/testing.md, "Faults injected"): SIMBOB_TEST_ODE_FAULT_AT_STEP=N gives the
// first moving body an angular velocity of 1e300 rad/s at the start of step N; ODE's integrator
// then fails its own check (dNormalize4) inside the step, the path a real ODE error takes.
uint64_t faultStepFromEnvironment() {
  const char* v = std::getenv("SIMBOB_TEST_ODE_FAULT_AT_STEP");
  if (!v || !*v) return 0;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(v, &end, 10);
  return end && *end == '\0' ? static_cast<uint64_t>(n) : 0;
}

void onOdeError(int num, const char* msg, va_list ap) { odeFatal("ODE error", num, msg, ap); }
void onOdeDebug(int num, const char* msg, va_list ap) { odeFatal("ODE internal error", num, msg, ap); }

// dInitODE2 once per process and never dCloseODE: ODE's global state outlives every World, so
// consecutive Worlds in one process (tests, batch runs) need no re-initialisation.
void initOdeOnce() {
  static const bool initialised = [] {
    dSetMessageHandler(onOdeMessage);
    dSetErrorHandler(onOdeError);
    dSetDebugHandler(onOdeDebug);
    return dInitODE2(0) != 0;
  }();
  (void)initialised;
}

// ODE's per-thread data (collision caches, with ODE's thread-local storage) must exist on every
// thread that creates, steps or destroys a World; ODE frees it when the thread ends (dInitODE2
// without dInitFlagManualThreadCleanup).
void allocateThreadData() {
  thread_local bool allocated = false;
  if (allocated) return;
  allocated = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
}

// Holds odeMutex() with the World's generator state swapped in (see above), and takes ODE's
// messages for the World (`im`; null while a World is destroyed).
class OdeSection {
 public:
  OdeSection(unsigned long& rng, WorldImpl* im) : lock_(odeMutex()), rng_(rng) {
    initOdeOnce();
    allocateThreadData();
    dRandSetSeed(rng_);
    sectionWorld.store(im, std::memory_order_release);
  }
  ~OdeSection() {
    sectionWorld.store(nullptr, std::memory_order_release);
    rng_ = dRandGetSeed();
  }
  OdeSection(const OdeSection&) = delete;
  OdeSection& operator=(const OdeSection&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
  unsigned long& rng_;
};

// Marks a World as being stepped; a second thread that calls step meanwhile is refused.
class InUse {
 public:
  explicit InUse(std::atomic<bool>& flag) : flag_(flag) {
    if (flag_.exchange(true, std::memory_order_acquire))
      throw std::logic_error(
          "World::step: this World is already being stepped on another thread; a World may be used "
          "from one thread at a time (give each thread a World of its own)");
  }
  ~InUse() { flag_.store(false, std::memory_order_release); }
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;

 private:
  std::atomic<bool>& flag_;
};

}  // namespace

std::mutex& odeMutex() { return processOdeMutex; }

WorldImpl::~WorldImpl() {
  // Contact joints first (they reference bodies), then the space with its geoms, then the
  // world with its bodies and remaining joints.
  if (contactGroup) dJointGroupDestroy(contactGroup);
  if (space) dSpaceDestroy(space);  // cleanup mode is on by default: destroys its geoms
  if (sensorSpace) dSpaceDestroy(sensorSpace);
  if (ray) dGeomDestroy(ray);
  if (rayReach) dGeomDestroy(rayReach);
  for (dGeomID r : rayScene.rays) dGeomDestroy(r);  // the threads' rays (rays.cpp), in no space
  if (rayScene.cleaner) dGeomDestroy(rayScene.cleaner);
  for (dTriMeshDataID d : triMeshData)  // after their geoms
    if (d) dGeomTriMeshDataDestroy(d);
  if (world) dWorldDestroy(world);
}

World::World() : impl_(new WorldImpl) {}

World::~World() {
  unsigned long rng = impl_->rng;  // the section writes it back after impl_ is gone
  OdeSection ode(rng, nullptr);    // no World's section: an ODE error here ends the process (odeFatal)
  impl_.reset();
}

namespace {
void buildWorld(WorldImpl& im, const Model& model, uint32_t seed, int threads);
}  // namespace

std::unique_ptr<World> World::create(const Model& model, uint32_t seed, int threads) {
  std::unique_ptr<World> w(new World());
  WorldImpl& im = *w->impl_;

  // The World's own generator starts at the seed, so QuickStep's constraint reordering is
  // reproducible (and the same as when each World was alone in its process).
  im.rng = seed;
  im.faultStep = faultStepFromEnvironment();
  OdeSection ode(im.rng, &im);
  try {
    buildWorld(im, model, seed, threads);
  } catch (const OdeFailure& e) {
    recordOdeFailure(im, e, "while the world was built");
  }
  return w;
}

namespace {
// What World::create builds, inside its ODE section.
void buildWorld(WorldImpl& im, const Model& model, uint32_t seed, int threads) {
  const SolverSettings& s = model.settings;
  im.world = dWorldCreate();
  dWorldSetGravity(im.world, s.gravity[0], s.gravity[1], s.gravity[2]);
  im.gravity = s.gravity;
  dWorldSetERP(im.world, s.erp);
  dWorldSetCFM(im.world, s.cfm);
  dWorldSetQuickStepNumIterations(im.world, s.iterations);
  im.quickstep = s.quickstep;
  im.space = createSpace(model);
  if (s.auto_disable) dWorldSetAutoDisableFlag(im.world, 1);
  im.contactGroup = dJointGroupCreate(0);
  im.contactBuffer.resize(static_cast<size_t>(std::max(1, s.max_contacts)));
  // The narrow phase and the ray sensors' rays run on these threads too (contacts.cpp, rays.cpp);
  // QuickStep, and everything that draws from ODE's generator or changes ODE's objects, stays
  // on the stepping thread.
  if (threads > 1) im.pool = std::make_unique<WorkerPool>(std::min(threads, kMaxThreads));

  // Model order within each concern, concerns in this order: the ODE call sequence is part of
  // what makes runs reproducible, so new concerns append here rather than interleave.
  createBodies(im, model);
  createGeoms(im, model);
  createJoints(im, model);
  createActuators(im, model);
  createSensors(im, model, seed);
  im.firstMessageInStep = false;  // a message while the World was built stays at t = 0, not at the first step's end
}
}  // namespace

void World::step(double h) {
  WorldImpl& im = *impl_;
  InUse busy(im.stepping);   // before the section: a refused call must not wait for the mutex
  if (im.odeFailed) return;  // World::failure says why
  OdeSection ode(im.rng, &im);
  try {
    ++im.stepsTaken;
    if (im.stepsTaken == im.faultStep && !im.bodies.empty()) dBodySetAngularVel(im.bodies.front(), 1e300, 1e300, 1e300);
    updateHingeStops(im);
    for (const auto& hook : im.beforeStep) hook(im, h);
    im.stepSize = h;
    collide(im);
    if (im.quickstep) {
      dWorldQuickStep(im.world, h);
    } else {
      dWorldStep(im.world, h);
    }
    dJointGroupEmpty(im.contactGroup);
    im.time_ns += std::llround(h * 1e9);  // the run's steps are whole nanoseconds
    if (im.firstMessageInStep) {  // read without the lock: the narrow phase's threads are done, none writes it now
      std::lock_guard<std::mutex> lock(im.messagesMutex);
      im.messages.first_time = static_cast<double>(im.time_ns) * 1e-9;
      im.firstMessageInStep = false;
    }
    updateJointTotals(im);
    if (!im.sensors.empty()) updateSensors(im, h);
  } catch (const OdeFailure& e) {
    recordOdeFailure(im, e, "in the step to t=" + formatNumber(static_cast<double>(im.time_ns) * 1e-9 + h) + " s");
  }
}

PhysicsMessages World::physicsMessages() const {
  std::lock_guard<std::mutex> lock(impl_->messagesMutex);
  return impl_->messages;
}

int World::bodyCount() const { return static_cast<int>(impl_->bodies.size()); }

namespace {
// A party (a plug-in) gave an index out of range: recorded, and the call does nothing.
bool inRange(WorldImpl& im, const char* call, int i, size_t n, const char* what) {
  if (i >= 0 && static_cast<size_t>(i) < n) return true;
  if (im.misuse.empty())
    im.misuse = std::string("World::") + call + "(" + std::to_string(i) + "): there is no " + what + " " +
                std::to_string(i) + " (the world has " + std::to_string(n) + ")";
  return false;
}
}  // namespace

const std::string& World::misuse() const { return impl_->misuse; }

BodyState World::body(int i) const {
  if (!inRange(*impl_, "body", i, impl_->bodies.size(), "body")) return BodyState{};
  return bodyState(*impl_, i);
}

int World::jointCount() const { return static_cast<int>(impl_->joints.size()); }

JointState World::joint(int i) const {
  if (!inRange(*impl_, "joint", i, impl_->joints.size(), "joint")) return JointState{};
  return jointState(*impl_, i);
}

int World::firstBrokenJoint(double limit, double* separation) const {
  const int n = jointCount();
  for (int i = 0; i < n; ++i) {
    double d = jointSeparation(*impl_, i);
    if (!(d <= limit)) {
      if (separation) *separation = d;
      return i;
    }
  }
  return -1;
}

int World::actuatorCount() const { return static_cast<int>(impl_->actuators.size()); }

void World::setCommand(int actuator, double value) {
  if (inRange(*impl_, "setCommand", actuator, impl_->actuators.size(), "actuator"))
    commandActuator(*impl_, actuator, value);
}

double World::driveEffort(int actuator) const {
  if (!inRange(*impl_, "driveEffort", actuator, impl_->actuators.size(), "actuator")) return 0;
  return impl_->actuators[static_cast<size_t>(actuator)].effort;
}

double World::stopTorque(int joint) const {
  if (!inRange(*impl_, "stopTorque", joint, impl_->joints.size(), "joint")) return 0;
  return simbob::stopTorque(*impl_, joint);
}

double World::command(int actuator) const {
  if (!inRange(*impl_, "command", actuator, impl_->actuators.size(), "actuator")) return 0;
  return impl_->actuators[static_cast<size_t>(actuator)].command;
}

int World::sensorCount() const { return static_cast<int>(impl_->sensors.size()); }

bool World::touching(int sensor) const {
  if (!inRange(*impl_, "touching", sensor, impl_->sensors.size(), "sensor")) return false;
  return impl_->sensors[static_cast<size_t>(sensor)].touching;
}

const std::vector<double>& World::sensorReading(int sensor) const {
  static const std::vector<double> kNone;
  if (!inRange(*impl_, "sensorReading", sensor, impl_->sensors.size(), "sensor")) return kNone;
  return impl_->sensors[static_cast<size_t>(sensor)].reading;
}

const std::vector<std::string>& World::sensorQuantities(int sensor) const {
  static const std::vector<std::string> kNone;
  if (!inRange(*impl_, "sensorQuantities", sensor, impl_->sensors.size(), "sensor")) return kNone;
  return impl_->sensors[static_cast<size_t>(sensor)].quantities;
}

int World::firstBadBody(double limit) const {
  // Runs after every step: read ODE's arrays in place. `!(|x| <= limit)` is also true for NaN;
  // an infinite limit still catches infinities through isfinite.
  auto bad = [limit](const dReal* v, int n) {
    for (int k = 0; k < n; ++k)
      if (!(std::fabs(v[k]) <= limit) || !std::isfinite(v[k])) return true;
    return false;
  };
  const int n = bodyCount();
  for (int i = 0; i < n; ++i) {
    dBodyID b = impl_->bodies[static_cast<size_t>(i)];
    if (bad(dBodyGetPosition(b), 3) || bad(dBodyGetLinearVel(b), 3) || bad(dBodyGetAngularVel(b), 3)) return i;
    const dReal* q = dBodyGetQuaternion(b);
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(q[k])) return i;
  }
  return -1;
}

int World::lastContactCount() const { return impl_->lastContacts; }

}  // namespace simbob
