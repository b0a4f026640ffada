/* Plug-ins that misuse the host or return what simbob refuses, for tests/cli/plugins_misuse.sh
 * (built there with cc, one per compile definition, against simbob/plugin_c.h alone). Each adds
 * the same three types, which behave until t = 0.5 s and then do the one wrong thing named by
 * the definition:
 * - MisuseController (refs Drive: an RCDriver, Sensor: any sensor): reads Sensor and commands
 *   Drive with 0 every Period. READ_NULL: read_sensor(host, 1, NULL, 8); READ_NEGATIVE:
 *   read_sensor(host, 1, out, -1); HOST_NULL: read_sensor(NULL, 1, out, 1); COMMAND_NAN,
 *   COMMAND_INF: set_command(host, 0, NaN or -inf).
 * - MisuseSensor (one quantity, "value"): reads t. MOUNT_NULL: mount_pose(host, NULL, q);
 *   VELOCITY_NULL: body_velocity(host, v, NULL); RAY_NULL: cast_ray(host, NULL, d, 1);
 *   READING_NAN, READING_INF: a reading of NaN or +inf; OVERFLOW: writes 4096 entries into its
 *   one-entry out.
 * - MisuseActuator (interface RCDriver): no force. HUGE_FORCE: a force of 1e300 N, finite. */
#include <math.h>
#include <stdio.h>

#include "simbob/plugin_c.h"

static void* create(const double* numbers, char* message) {
  static int instance;
  (void)numbers;
  (void)message;
  return &instance;
}

static int controller_act(void* user, const SimbobHost* host, double t, char* message) {
  double out[8] = {0};
  double command = 0;
  (void)user;
  (void)message;
  if (t >= 0.5) {
#if defined(READ_NULL)
    return host->read_sensor(host, 1, NULL, 8) < 0;
#elif defined(READ_NEGATIVE)
    return host->read_sensor(host, 1, out, -1) < 0;
#elif defined(HOST_NULL)
    return host->read_sensor(NULL, 1, out, 1) < 0;
#elif defined(COMMAND_NAN)
    command = NAN;
#elif defined(COMMAND_INF)
    command = -INFINITY;
#endif
  }
  if (host->read_sensor(host, 1, out, 8) != 1) return 1;
  return host->set_command(host, 0, command) != 0;
}

static int sensor_read(void* user, const SimbobHost* host, double t, double* out, int n, char* message) {
  double q[4], v[3];
  const double d[3] = {1, 0, 0};
  (void)user;
  (void)message;
  (void)q;
  (void)v;
  (void)d;
  (void)n;
  out[0] = t;
  if (t >= 0.5) {
#if defined(MOUNT_NULL)
    return host->mount_pose(host, NULL, q) != 0;
#elif defined(VELOCITY_NULL)
    return host->body_velocity(host, v, NULL) != 0;
#elif defined(RAY_NULL)
    return host->cast_ray(host, NULL, d, 1.0) < 0;
#elif defined(READING_NAN)
    out[0] = NAN;
#elif defined(READING_INF)
    out[0] = INFINITY;
#elif defined(OVERFLOW)
    for (int k = 0; k < 4096; ++k) out[k] = k;
#endif
  }
  return 0;
}

static int actuator_apply(void* user, const SimbobHost* host, double t, double dt, double command, double force[3],
                          double torque[3], char* message) {
  (void)user;
  (void)host;
  (void)dt;
  (void)command;
  (void)message;
  force[0] = force[1] = force[2] = 0;
  torque[0] = torque[1] = torque[2] = 0;
#ifdef HUGE_FORCE
  if (t >= 0.5) force[0] = 1e300;
#else
  (void)t;
#endif
  return 0;
}

static const char* const kQuantities[] = {"value"};
static const SimbobRef kRefs[] = {{"Drive", "RCDriver", "what it commands"}, {"Sensor", "RCSensor", "what it reads"}};

static const SimbobType kTypes[] = {
    {SIMBOB_CONTROLLER, "MisuseController", "misuses the host after 0.5 s", NULL, 0, kRefs, 2, NULL, 0, NULL, create,
     NULL, controller_act, NULL, NULL},
    {SIMBOB_SENSOR, "MisuseSensor", "misuses the host after 0.5 s", NULL, 0, NULL, 0, kQuantities, 1, NULL, create,
     NULL, NULL, sensor_read, NULL},
    {SIMBOB_ACTUATOR, "MisuseActuator", "misuses the host after 0.5 s", NULL, 0, NULL, 0, NULL, 0, NULL, create, NULL,
     NULL, NULL, actuator_apply},
};

static const SimbobPlugin kPlugin = {SIMBOB_PLUGIN_ABI_VERSION, "misuse", kTypes, 3};

const SimbobPlugin* simbob_plugin_v2(void) { return &kPlugin; }
