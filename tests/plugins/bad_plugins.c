/* Deliberately wrong plug-ins for tests/cli/plugins.sh, in C99 against simbob/plugin_c.h, one per
 * compile definition: BAD_ABI (abi_version 999), DUPLICATE (a controller called RCDriveTest, a
 * built-in's name), NO_ENTRY (no entry point), V1 (only the old C++ ABI's simbob_plugin_v1),
 * NO_READ (a sensor type without read), and plug-ins adding the controller type BadController
 * (no parameters but Period) that fails in one place: CREATE_FAILS (create returns NULL),
 * ACT_FAILS (act returns 1 at t >= 0.5 s), BAD_INDEX (set_command(99999) at t >= 0.5 s),
 * NEG_INDEX (set_command(-1)), CONTROLLER_RAY (cast_ray, which is for sensors and actuators);
 * SENSOR_FAILS adds the sensor type BadSensor whose read fails at t >= 0.5 s, ACTUATOR_NAN the
 * actuator type BadActuator whose force is not a number. */
#include <math.h>
#include <stdio.h>

#include "simbob/plugin_c.h"

#ifndef NO_ENTRY

static void* create(const double* numbers, char* message) {
  static int instance;
  (void)numbers;
#ifdef CREATE_FAILS
  snprintf(message, SIMBOB_MESSAGE_SIZE, "create failed on purpose");
  return NULL;
#else
  (void)message;
  return &instance;
#endif
}

static int act(void* user, const SimbobHost* host, double t, char* message) {
  (void)user;
  (void)message;
  if (t >= 0.5) {
#if defined(ACT_FAILS)
    snprintf(message, SIMBOB_MESSAGE_SIZE, "act failed on purpose at t=%g", t);
    return 1;
#elif defined(BAD_INDEX)
    host->set_command(host, 99999, 1.0);
#elif defined(NEG_INDEX)
    host->set_command(host, -1, 1.0);
#elif defined(CONTROLLER_RAY)
    const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
    host->cast_ray(host, o, d, 1.0);
#endif
  }
  (void)host;
  return 0;
}

static int read_value(void* user, const SimbobHost* host, double t, double* out, int n, char* message) {
  (void)user;
  (void)host;
  (void)n;
  if (t >= 0.5) {
    snprintf(message, SIMBOB_MESSAGE_SIZE, "read failed on purpose at t=%g", t);
    return 1;
  }
  out[0] = t;
  return 0;
}

static int apply_nan(void* user, const SimbobHost* host, double t, double dt, double command, double force[3],
                     double torque[3], char* message) {
  (void)user;
  (void)host;
  (void)t;
  (void)dt;
  (void)command;
  (void)message;
  force[0] = NAN;
  force[1] = force[2] = 0;
  torque[0] = torque[1] = torque[2] = 0;
  return 0;
}

static const char* const kQuantities[] = {"t"};

#if defined(DUPLICATE)
#define TYPE_NAME "RCDriveTest"
#else
#define TYPE_NAME "BadController"
#endif

static const SimbobType kTypes[] = {
#if defined(ACTUATOR_NAN)
    {SIMBOB_ACTUATOR, "BadActuator", "fails", NULL, 0, NULL, 0, NULL, 0, NULL, create, NULL, NULL, NULL, apply_nan},
#elif defined(SENSOR_FAILS) || defined(NO_READ)
    {SIMBOB_SENSOR, "BadSensor", "fails", NULL, 0, NULL, 0, kQuantities, 1, NULL, create, NULL, NULL,
#ifdef NO_READ
     NULL,
#else
     read_value,
#endif
     NULL},
#else
    {SIMBOB_CONTROLLER, TYPE_NAME, "fails", NULL, 0, NULL, 0, NULL, 0, NULL, create, NULL, act, NULL, NULL},
#endif
};

#ifdef BAD_ABI
static const SimbobPlugin kPlugin = {999u, "bad_abi", kTypes, 1};
#elif defined(DUPLICATE)
static const SimbobPlugin kPlugin = {SIMBOB_PLUGIN_ABI_VERSION, "duplicate", kTypes, 1};
#else
static const SimbobPlugin kPlugin = {SIMBOB_PLUGIN_ABI_VERSION, "bad", kTypes, 1};
#endif

#ifdef V1
const void* simbob_plugin_v1(void);
const void* simbob_plugin_v1(void) { return &kPlugin; }
#else
const SimbobPlugin* simbob_plugin_v2(void) { return &kPlugin; }
#endif

#else
int simbob_not_a_plugin(void);
int simbob_not_a_plugin(void) { return 0; }
#endif
