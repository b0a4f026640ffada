/* Test plug-ins in plain C for tests/cli/plugins_c.sh (built there with clang, against
 * simbob/plugin_c.h alone):
 * - Thruster (actuator, interface RCDriver): pushes its body along its mount's +X with
 *   Force * command N (the command as controllers give it, unclamped), no torque.
 * - Throttle (controller): from Start s on, commands ref 0 (an RCDriver) with Command while the
 *   body behind ref 2 (RCBody) is short of x = StopX m (read with body_state), else with 0. Before
 *   it commands, it reads ref 1 (any sensor) and fails unless the reading has exactly one entry
 *   that is a finite number: a controller in C that reads a sensor and a body. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "simbob/plugin_c.h"

/* --- Thruster --- */
static void* thruster_create(const double* numbers, char* message) {
  double* force = (double*)malloc(sizeof(double));
  if (!force) {
    snprintf(message, SIMBOB_MESSAGE_SIZE, "out of memory");
    return NULL;
  }
  *force = numbers[0];
  return force;
}

static int thruster_apply(void* user, const SimbobHost* host, double t, double dt, double command, double force[3],
                          double torque[3], char* message) {
  (void)host;
  (void)t;
  (void)dt;
  (void)message;
  force[0] = *(const double*)user * command;
  force[1] = force[2] = 0;
  torque[0] = torque[1] = torque[2] = 0;
  return 0;
}

/* --- Throttle --- */
typedef struct Throttle {
  double start, command, stop_x;
} Throttle;

static void* throttle_create(const double* numbers, char* message) {
  Throttle* c = (Throttle*)malloc(sizeof(Throttle));
  if (!c) {
    snprintf(message, SIMBOB_MESSAGE_SIZE, "out of memory");
    return NULL;
  }
  c->start = numbers[0];
  c->command = numbers[1];
  c->stop_x = numbers[2];
  return c;
}

static int throttle_act(void* user, const SimbobHost* host, double t, char* message) {
  const Throttle* c = (const Throttle*)user;
  double reading[4], position[3];
  const int n = host->read_sensor(host, 1, reading, 4);
  if (n != 1 || !isfinite(reading[0])) {
    snprintf(message, SIMBOB_MESSAGE_SIZE, "ref 1 read %d values", n);
    return 1;
  }
  if (host->body_state(host, 2, position, NULL, NULL, NULL) != 0) return 1;
  return host->set_command(host, 0, t >= c->start - 1e-9 && position[0] < c->stop_x ? c->command : 0.0) == 0 ? 0 : 1;
}

static const SimbobNumber kThrusterNumbers[] = {{"Force", 1.0, "N", "force at command 1"}};
static const SimbobNumber kThrottleNumbers[] = {{"Start", 0.0, "s", "when to start commanding"},
                                                {"Command", 1.0, "", "the command from Start on"},
                                                {"StopX", 1e9, "m", "commands 0 once the body is this far along X"}};
static const SimbobRef kThrottleRefs[] = {{"Drive", "RCDriver", "what it commands"},
                                          {"Sensor", "RCSensor", "a sensor it reads"},
                                          {"Body", "RCBody", "the body whose x it watches"}};

static const SimbobType kTypes[] = {
    {SIMBOB_ACTUATOR, "Thruster", "A force along the mount's +X: Force * command (test plug-in).", kThrusterNumbers, 1,
     NULL, 0, NULL, 0, "RCDriver", thruster_create, free, NULL, NULL, thruster_apply},
    {SIMBOB_CONTROLLER, "Throttle", "Commands Command from Start on (test plug-in).", kThrottleNumbers, 3,
     kThrottleRefs, 3, NULL, 0, NULL, throttle_create, free, throttle_act, NULL, NULL},
};

static const SimbobPlugin kPlugin = {SIMBOB_PLUGIN_ABI_VERSION, "c_plugins", kTypes, 2};

const SimbobPlugin* simbob_plugin_v2(void) { return &kPlugin; }
