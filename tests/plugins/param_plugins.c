/* Plug-ins whose parameter lists simbob must refuse or bound, for tests/cli/plugins_params.sh
 * (built there with cc, one per compile definition, against simbob/plugin_c.h alone):
 * - SENSOR_POSE, SENSOR_PERIOD, ACTUATOR_POSE: a sensor (actuator) with a number named Pose or
 *   Period, the parameters simbob gives every plug-in periphery (an actuator has no Period:
 *   ACTUATOR_POSE with POSE_NAME="Period" names its number Period);
 * - CONTROLLER_PERIOD: a controller with a number named Period; REF_PERIOD: one with a ref named
 *   Period; TWO_GAINS: two numbers named Gain; GAIN_CASE: numbers Gain and gain (INI keys
 *   ignore case); NUMBER_IS_REF: a number and a ref both named Drive;
 * - NUMBERS=N: a controller (ManyNumbers) with N numbers N0 .. N<N-1>, default k for number k,
 *   that fails unless create() got them all, in order;
 * - QUANTITIES=N: a sensor (ManyQuantities) with N quantities q0 .. q<N-1>.
 * The names are built when simbob asks for the plug-in (static storage, as the ABI wants). */
#include <stdio.h>
#include <stdlib.h>

#include "simbob/plugin_c.h"

static void* create(const double* numbers, char* message) {
  static int instance;
#ifdef NUMBERS
  for (int k = 0; k < NUMBERS; ++k)
    if (numbers[k] != (double)k) {
      snprintf(message, SIMBOB_MESSAGE_SIZE, "number %d is %g, not %d", k, numbers[k], k);
      return NULL;
    }
#else
  (void)numbers;
  (void)message;
#endif
  return &instance;
}

static int act(void* user, const SimbobHost* host, double t, char* message) {
  (void)user;
  (void)host;
  (void)t;
  (void)message;
  return 0;
}

static int read_value(void* user, const SimbobHost* host, double t, double* out, int n, char* message) {
  (void)user;
  (void)host;
  (void)message;
  for (int k = 0; k < n; ++k) out[k] = t;
  return 0;
}

static int apply(void* user, const SimbobHost* host, double t, double dt, double command, double force[3],
                 double torque[3], char* message) {
  (void)user;
  (void)host;
  (void)t;
  (void)dt;
  (void)command;
  (void)message;
  force[0] = force[1] = force[2] = 0;
  torque[0] = torque[1] = torque[2] = 0;
  return 0;
}

#ifndef POSE_NAME
#define POSE_NAME "Pose"
#endif

static const char* const kQuantities[] = {"value"};
static SimbobType type;
static SimbobPlugin plugin = {SIMBOB_PLUGIN_ABI_VERSION, "params", &type, 1};

static void set_numbers(const char* a, const char* b) {
  static SimbobNumber numbers[2];
  numbers[0].name = a;
  numbers[0].unit = "";
  numbers[0].doc = "a number";
  numbers[1] = numbers[0];
  numbers[1].name = b;
  type.numbers = numbers;
  type.number_count = b ? 2 : 1;
}

static void controller(const char* name) {
  type.kind = SIMBOB_CONTROLLER;
  type.name = name;
  type.doc = "a controller (test plug-in)";
  type.create = create;
  type.act = act;
}

static void periphery(unsigned kind, const char* name) {
  type.kind = kind;
  type.name = name;
  type.doc = "a periphery (test plug-in)";
  type.create = create;
  if (kind == SIMBOB_SENSOR) {
    type.read = read_value;
    type.quantities = kQuantities;
    type.quantity_count = 1;
  } else {
    type.apply = apply;
  }
}

const SimbobPlugin* simbob_plugin_v2(void) {
  static const SimbobRef refs[] = {{"Drive", "RCDriver", "a drive"}, {"Period", "RCSensor", "a sensor"}};
#if defined(SENSOR_POSE)
  periphery(SIMBOB_SENSOR, "PoseSensor");
  set_numbers("Gain", "Pose");
#elif defined(SENSOR_PERIOD)
  periphery(SIMBOB_SENSOR, "PeriodSensor");
  set_numbers("Period", NULL);
#elif defined(ACTUATOR_POSE)
  periphery(SIMBOB_ACTUATOR, "PoseActuator");
  set_numbers(POSE_NAME, NULL);
#elif defined(CONTROLLER_PERIOD)
  controller("PeriodController");
  set_numbers("Gain", "Period");
#elif defined(REF_PERIOD)
  controller("RefPeriodController");
  type.refs = refs;
  type.ref_count = 2;
#elif defined(TWO_GAINS)
  controller("TwoGains");
  set_numbers("Gain", "Gain");
#elif defined(GAIN_CASE)
  controller("GainCase");
  set_numbers("Gain", "gain");
#elif defined(NUMBER_IS_REF)
  controller("NumberIsRef");
  set_numbers("Drive", NULL);
  type.refs = refs;
  type.ref_count = 1;
#elif defined(NUMBERS)
  controller("ManyNumbers");
  static SimbobNumber numbers[NUMBERS];
  static char names[NUMBERS][16];
  for (int k = 0; k < NUMBERS; ++k) {
    snprintf(names[k], sizeof names[k], "N%d", k);
    numbers[k].name = names[k];
    numbers[k].default_value = k;
    numbers[k].unit = "";
    numbers[k].doc = "";
  }
  type.numbers = numbers;
  type.number_count = NUMBERS;
#elif defined(QUANTITIES)
  periphery(SIMBOB_SENSOR, "ManyQuantities");
  static const char* quantities[QUANTITIES];
  static char names[QUANTITIES][16];
  for (int k = 0; k < QUANTITIES; ++k) {
    snprintf(names[k], sizeof names[k], "q%d", k);
    quantities[k] = names[k];
  }
  type.quantities = quantities;
  type.quantity_count = QUANTITIES;
#endif
  return &plugin;
}
