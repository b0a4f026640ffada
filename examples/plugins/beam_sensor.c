/* Example plug-in in plain C (docs/plugins.md): the sensor type BeamSensor, a one-ray distance
 * sensor like RCRangeSensor. It casts one ray from its mount along the mount's -Z and reads the
 * distance (m) to the first geom of another body, clamped to [MinRange, MaxRange]; MaxRange when
 * nothing is hit. It offers the interface RCRangeSensor, so RCObstacleAvoider reads it like a
 * built-in range sensor. Needs nothing but simbob/plugin_c.h:
 *   cc -std=c99 -shared -fPIC -I include examples/plugins/beam_sensor.c -o beam_sensor.so
 *   build/simbob run examples/plugins/beam_robot.xml --plugin beam_sensor.so */
#include <stdlib.h>

#include "simbob/plugin_c.h"

typedef struct Beam {
  double min_range, max_range; /* m */
} Beam;

/* numbers[] in the order kNumbers declares them. */
static void* beam_create(const double* numbers, char* message) {
  Beam* b;
  (void)message;
  b = (Beam*)malloc(sizeof(Beam));
  if (!b) return NULL; /* an empty message reads "(no message)" */
  b->min_range = numbers[0];
  b->max_range = numbers[1];
  return b;
}

static void beam_destroy(void* user) { free(user); }

static int beam_read(void* user, const SimbobHost* host, double t, double* out, int n, char* message) {
  const Beam* b = (const Beam*)user;
  const double origin[3] = {0, 0, 0}, forward[3] = {0, 0, -1}; /* in the mount frame */
  double d = host->cast_ray(host, origin, forward, b->max_range);
  (void)t;
  (void)n; /* n is the one quantity */
  (void)message;
  if (d < 0) d = b->max_range; /* nothing within MaxRange */
  if (d < b->min_range) d = b->min_range;
  out[0] = d;
  return 0;
}

static const SimbobNumber kNumbers[] = {
    {"MinRange", 0.0, "m", "closest distance it measures: a nearer hit reads MinRange"},
    {"MaxRange", 5.0, "m", "farthest distance it measures, and the reading when nothing is hit"},
};
static const char* const kQuantities[] = {"distance"};

/* C99 designated initializers: the fields a sensor does not use (refs, act, apply) stay 0. */
static const SimbobType kTypes[] = {{
    .kind = SIMBOB_SENSOR,
    .name = "BeamSensor",
    .doc = "One ray along the mount's -Z: the distance to the first geom of another body (example plug-in in C).",
    .numbers = kNumbers,
    .number_count = 2,
    .quantities = kQuantities,
    .quantity_count = 1,
    .interface = "RCRangeSensor", /* reading[0] a distance along -Z, numbers MinRange and MaxRange */
    .create = beam_create,
    .destroy = beam_destroy,
    .read = beam_read,
}};

static const SimbobPlugin kPlugin = {SIMBOB_PLUGIN_ABI_VERSION, "beam_sensor", kTypes, 1};

const SimbobPlugin* simbob_plugin_v2(void) { return &kPlugin; }
