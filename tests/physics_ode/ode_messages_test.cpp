// What ODE says goes through simbob (lib/physics/world.cpp, its handlers): a message during a
// step is the World's (World::physicsMessages), never a line of ODE's own on stderr; an error or
// a failed check of ODE's inside a World's step is that World's failure (it is not stepped
// again); outside every World it ends the process with simbob's one line and exit status 70
// instead of ODE's exit(1) or abort().
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "physics/world_impl.h"
#include "shipped_scene.h"

namespace {

using simbob::World;

// What the process writes to its stderr (file descriptor 2) while `f` runs.
template <class F>
std::string stderrOf(F f) {
  std::fflush(stderr);
  std::FILE* tmp = std::tmpfile();
  REQUIRE(tmp);
  const int saved = dup(2);
  REQUIRE(saved >= 0);
  REQUIRE(dup2(fileno(tmp), 2) == 2);
  f();
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  std::string text;
  std::rewind(tmp);
  for (int c; (c = std::fgetc(tmp)) != EOF;) text += static_cast<char>(c);
  std::fclose(tmp);
  return text;
}

}  // namespace

TEST_CASE("ODE's messages while stepping are the World's, not lines on stderr", "[physics][ode]") {
  // The guide's box stack under Solver Step with no constraint force mixing: dWorldStep's LCP
  // solver meets contacts it cannot meet exactly (the boxes rest on four points each, more than
  // a box needs) and ODE says "LCP internal error" (dMessage 3), many times in a second.
  simbob::Model m = simbob::test::shippedScene("box_stack");
  m.settings.quickstep = false;
  m.settings.cfm = 0;
  const double h = m.settings.max_time_step;
  constexpr int kSteps = 1000;
  std::unique_ptr<World> w;
  const std::string err = stderrOf([&] {
    w = World::create(m, 0);
    for (int i = 0; i < kSteps; ++i) w->step(h);
  });
  CHECK(err == "");
  const simbob::PhysicsMessages msg = w->physicsMessages();
  CHECK(msg.count > 1);
  CHECK(msg.first.rfind("ODE message 3: LCP internal error", 0) == 0);
  CHECK(msg.first.find('\n') == std::string::npos);
  // The end of a step that came after the first: a whole number of steps of 1 ms.
  CHECK(msg.first_time > 0);
  CHECK(msg.first_time <= kSteps * h);
  CHECK(std::fabs(msg.first_time / h - std::round(msg.first_time / h)) < 1e-9);

  // The same scene as it is written (QuickStep) gives ODE nothing to say.
  const simbob::Model quick = simbob::test::shippedScene("box_stack");
  std::unique_ptr<World> q = World::create(quick, 0);
  for (int i = 0; i < kSteps; ++i) q->step(h);
  CHECK(q->physicsMessages().count == 0);
  CHECK(q->physicsMessages().first.empty());
}

TEST_CASE("an error of ODE's outside every World ends the process with one line and status 70", "[physics][ode]") {
  // In a child process: a World installs simbob's handlers, then a joint between a body and
  // itself fails ODE's own check (dUASSERT, which Debian's ODE keeps) -- what the compile step
  // never lets a scene do.
  int out[2];
  REQUIRE(pipe(out) == 0);
  std::fflush(nullptr);
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    dup2(out[1], 2);
    close(out[0]);
    const simbob::Model m = simbob::test::shippedScene("pendulum");
    std::unique_ptr<World> w = World::create(m, 0);
    dWorldID world = dWorldCreate();
    dBodyID b = dBodyCreate(world);
    dJointAttach(dJointCreateBall(world, nullptr), b, b);
    std::_Exit(0);  // not reached: ODE's check does not return
  }
  close(out[1]);
  std::string text;
  char buf[256];
  for (ssize_t n; (n = read(out[0], buf, sizeof buf)) > 0;) text.append(buf, static_cast<size_t>(n));
  close(out[0]);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 70);
  CHECK(text.rfind("simbob: error: internal error: ODE internal error 2: can't have body1==body2 in dJointAttach()",
                   0) == 0);
  CHECK(text.find('\n') == text.size() - 1);  // one line
}

TEST_CASE("an error of ODE's inside a World's step is that World's failure: it is not stepped again, others go on",
          "[physics][ode]") {
  // SIMBOB_TEST_ODE_FAULT_AT_STEP (world.cpp) gives the first body an angular velocity of 1e300
  // rad/s at the start of that step: ODE's integrator fails its own check (dNormalize4) inside
  // dWorldQuickStep, and the exception crosses ODE's frames to World::step.
  const simbob::Model m = simbob::test::shippedScene("pendulum");
  const double h = m.settings.max_time_step;
  REQUIRE(setenv("SIMBOB_TEST_ODE_FAULT_AT_STEP", "3", 1) == 0);
  std::unique_ptr<World> w = World::create(m, 0);
  REQUIRE(unsetenv("SIMBOB_TEST_ODE_FAULT_AT_STEP") == 0);
  std::unique_ptr<World> other = World::create(m, 0);
  std::string err = stderrOf([&] {
    for (int i = 0; i < 5; ++i) {
      w->step(h);
      other->step(h);
    }
  });
  CHECK(err == "");
  const simbob::Error* e = w->failure();
  REQUIRE(e);
  CHECK(e->kind == simbob::ErrorKind::Internal);
  CHECK(e->message.rfind("internal error: ODE internal error 1: assertion \"!bSafeNormalize4Fault\" failed", 0) == 0);
  CHECK(e->message.find("in the step to t=0.003 s") != std::string::npos);
  CHECK(e->message.find("this world is not stepped again") != std::string::npos);
  // Two steps taken, the third failed (its state is ODE's half-updated one, NaN here), and the
  // World has not moved since: the same bits.
  const simbob::BodyState after = w->body(0);
  w->step(h);
  const simbob::BodyState later = w->body(0);
  CHECK(std::memcmp(&later.pose, &after.pose, sizeof after.pose) == 0);
  // The other World is untouched: it steps as a World alone does.
  CHECK_FALSE(other->failure());
  std::unique_ptr<World> alone = World::create(m, 0);
  for (int i = 0; i < 5; ++i) alone->step(h);
  CHECK(other->body(0).pose.p == alone->body(0).pose.p);
  CHECK(other->body(0).pose.q == alone->body(0).pose.q);
}
