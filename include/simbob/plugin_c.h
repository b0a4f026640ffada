/* simbob plug-in ABI, version 3 (docs/plugins.md): plain C99, so a plug-in built by any compiler,
 * or in any language with a C FFI, loads into any simbob that speaks this version.
 *
 * A plug-in is a shared library that defines one function,
 *
 *     const SimbobPlugin* simbob_plugin_v2(void);
 *
 * returning a SimbobPlugin (abi_version = SIMBOB_PLUGIN_ABI_VERSION) that lists the component
 * types it adds: controllers, sensors and actuators. simbob registers them like its built-in
 * types (scene files, `simbob check`, `simbob types`). For every component of such a type in a
 * scene simbob calls create() with its number parameters, then, while the run goes:
 *   - a controller's act() at 0, Period, 2 Period, ... (s of simulated time);
 *   - a sensor's read() on the step grid (every step, or at its Period like a built-in sensor);
 *   - an actuator's apply() before every step, with the command controllers gave it;
 * and destroy() when the run ends. Each callback gets the instance pointer create() returned
 * (`user`) and a SimbobHost: simbob's function table for this instance (reading sensors,
 * commanding actuators, body poses, casting rays). Nothing but plain C crosses the boundary; a
 * callback that fails returns nonzero (create: NULL) after writing a message, at most
 * SIMBOB_MESSAGE_SIZE bytes with its terminating NUL, into `message`; the run stops with an
 * error naming the scene element, the plug-in and the type. Callbacks must not throw (C++) or
 * longjmp out. Units are SI (m, s, rad, N, N m); frames are right-handed, Y up; a quaternion is
 * (w, x, y, z). */
#ifndef SIMBOB_PLUGIN_C_H
#define SIMBOB_PLUGIN_C_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The ABI version this header describes; SimbobPlugin.abi_version must equal it. (Versions 1
 * and 2 were the C++ ABI with the entry point simbob_plugin_v1, no longer loaded.) */
#define SIMBOB_PLUGIN_ABI_VERSION 3u

/** Capacity of every `message` buffer, terminating NUL included. */
#define SIMBOB_MESSAGE_SIZE 256

/** SimbobType.kind */
#define SIMBOB_CONTROLLER 1u
#define SIMBOB_SENSOR 2u
#define SIMBOB_ACTUATOR 3u

/** A number parameter (a scene element <Name Value="..."/>); its value reaches create() in
 * declaration order. */
typedef struct SimbobNumber {
  const char* name;
  double default_value;
  const char* unit; /**< "m", "s", ... or "" */
  const char* doc;  /**< one line for `simbob types` */
} SimbobNumber;

/** A controller's reference parameter (<Name Ref="Robot.Part.Key"/>) to a periphery that
 * offers `interface`: an actuator ("RCDriver", "RCPosControl", "RCVelControl", or an actuator
 * type's own interface) it commands with set_command, a sensor ("RCSensor": any sensor,
 * "RCRangeSensor", "RCLaserScanner", ...) it reads with read_sensor, or ("RCBody") a mobile body
 * whose state it reads with body_state. */
typedef struct SimbobRef {
  const char* name;
  const char* interface;
  const char* doc;
} SimbobRef;

typedef struct SimbobHost SimbobHost;

/** simbob's side of one instance: call its functions with the host itself as first argument.
 * Valid only during the callback that received it. Every function returns 0 (or a count) on
 * success and -1 for an argument out of range, which also stops the run with an error: a ref out
 * of range, a NULL host or one from another callback, a NULL pointer (body_state alone takes
 * NULL for what it need not write), a negative n, a command that is not finite. */
struct SimbobHost {
  uint32_t size; /**< sizeof(SimbobHost) as simbob built it */
  void* context; /**< simbob's; do not touch */
  /** Simulated time, s. */
  double (*time)(const SimbobHost* host);
  /** Controllers: reads the sensor behind ref `ref` (index into SimbobType.refs) into out[0..n-1];
   * returns the length of its reading (which may exceed n: the rest is not written). */
  int (*read_sensor)(const SimbobHost* host, int ref, double* out, int n);
  /** Controllers: commands the actuator behind ref `ref` from now on (its unit: a drive's voltage,
   * a servo's target position, a velocity drive's target velocity, a plug-in actuator's command). */
  int (*set_command)(const SimbobHost* host, int ref, double value);
  /** Sensors and actuators: the global pose of their mount (the body's frame composed with the
   * Pose parameter): position (m) and quaternion (w, x, y, z). */
  int (*mount_pose)(const SimbobHost* host, double position[3], double quaternion[4]);
  /** Sensors and actuators: the global linear (m/s) and angular (rad/s) velocity of the body they
   * are attached to (zeros for a static mount). */
  int (*body_velocity)(const SimbobHost* host, double linear[3], double angular[3]);
  /** The state of a mobile body: for a controller the one behind ref `ref` (interface "RCBody");
   * for a sensor or actuator (ref -1) the body it rides on (the identity pose at the origin and
   * zeros for a static mount). Global: position (m), quaternion (w, x, y, z) of the body's
   * frame, linear (m/s) and angular (rad/s) velocity. Any pointer may be NULL. */
  int (*body_state)(const SimbobHost* host, int ref, double position[3], double quaternion[4], double linear[3],
                    double angular[3]);
  /** Sensors and actuators: casts a ray from `origin` along `direction` (both in the mount frame;
   * the direction need not be unit) against every geom of another body (its own body and bodies
   * joined to it are not seen, also on a static mount; every other geom is). Returns the
   * distance (m) to the first hit, or -1 when nothing is hit within max_length (in (0, 1e6] m).
   * The same world gives the same answer. */
  double (*cast_ray)(const SimbobHost* host, const double origin[3], const double direction[3], double max_length);
};

/** A component type a plug-in adds. Fields a kind does not use are 0 / NULL. */
typedef struct SimbobType {
  uint32_t kind;    /**< SIMBOB_CONTROLLER, SIMBOB_SENSOR or SIMBOB_ACTUATOR */
  const char* name; /**< the scene element; must not be taken by a built-in or another plug-in */
  const char* doc;  /**< one line for `simbob types` */
  const SimbobNumber* numbers;
  int number_count;
  /** Controllers: the refs, in the order read_sensor and set_command number them. */
  const SimbobRef* refs;
  int ref_count;
  /** Sensors: the names of the reading's entries ("distance", "bearing", ...); the reading has
   * quantity_count entries. */
  const char* const* quantities;
  int quantity_count;
  /** Sensors: an interface it offers built-in controllers, or NULL. "RCRangeSensor": reading[0]
   * is a distance (m) along the mount's -Z, and the type has the numbers MinRange and MaxRange
   * (the reading when nothing is seen), so RCObstacleAvoider can read it.
   * Actuators: "RCDriver" (the default when NULL) or another name controllers refer to it by. */
  const char* interface;

  /** Makes an instance from the number parameters (number_count values, declaration order).
   * Returns the instance (any non-NULL pointer) or NULL after writing why into message. May be
   * NULL: instances are then NULL too. */
  void* (*create)(const double* numbers, char* message);
  /** Frees an instance (may be NULL). */
  void (*destroy)(void* user);
  /** Controllers: acts at simulated time t (s). */
  int (*act)(void* user, const SimbobHost* host, double t, char* message);
  /** Sensors: writes the reading at time t (s) into out[0..n-1], n = quantity_count, every entry
   * finite (a NaN or infinite entry, or a write past out[n-1], stops the run with an error). */
  int (*read)(void* user, const SimbobHost* host, double t, double* out, int n, char* message);
  /** Actuators: the force (N) and torque (N m), in the mount frame, to apply at the mount's origin
   * during the next step of dt s, given the latest command (0 before the first). */
  int (*apply)(void* user, const SimbobHost* host, double t, double dt, double command, double force[3],
               double torque[3], char* message);
} SimbobType;

/** What simbob_plugin_v2 returns (static storage: simbob keeps pointers into it). */
typedef struct SimbobPlugin {
  uint32_t abi_version; /**< SIMBOB_PLUGIN_ABI_VERSION */
  const char* name;     /**< for messages */
  const SimbobType* types;
  int type_count;
} SimbobPlugin;

/** The entry point every plug-in defines. */
const SimbobPlugin* simbob_plugin_v2(void);

#ifdef __cplusplus
}
#endif

#endif /* SIMBOB_PLUGIN_C_H */
