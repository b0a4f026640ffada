/* The example peer of scenes/socket_robot.xml in C, through simbob_client.c: the control law of
 * scripts/simbob_client.py (forward at 0.2 m/s for 2 s, then a proportional turn to face a
 * quarter turn to the left), so it drives the robot to the same trajectory bytes.
 *   cc -std=c99 -O2 -ffp-contract=off -o drive_two_wheel drive_two_wheel.c -lm
 *   simbob run scenes/socket_robot.xml --duration 10 --controller Bot.Cart.Link=./drive_two_wheel
 * `drive_two_wheel probe` prints what a conformance test compares between clients. */
#include "simbob_client.c" /* first: it sets the POSIX feature macro */

#include <math.h>

#define PI 3.141592653589793 /* Python's math.pi */

static double heading(const double* q) { /* rotation about +Y of a body whose forward is +X */
  double w = q[0], x = q[1], y = q[2], z = q[3];
  double fx = 1 - 2 * (y * y + z * z);
  double fz = 2 * (x * z - w * y);
  return atan2(-fz, fx);
}

static int probe(sb_client* c) {
  printf("version %d\nkey %s\n", c->version, c->key);
  for (int i = 0; i < c->n_motions; ++i) printf("motion %s\n", c->motions[i].key);
  for (int i = 0; i < c->n_bodies; ++i) printf("body %s\n", c->bodies[i].key);
  for (int i = 0; i < c->n_sensors; ++i) printf("sensor %s %s %d\n", c->sensors[i].key, c->sensors[i].kind, c->sensors[i].n);
  const char* first = c->bodies[0].key;
  sb_subscribe(c, "bodies", 1, &first);
  sb_subscribe(c, "joints", 0, NULL);
  double v[2] = {0.5, 0.0};
  sb_set(c, c->motions[0].key, 2, v);
  if (sb_state(c) != 1 || sb_step(c) != 0 || sb_state(c) != 1) return 1;
  printf("t %.3f\n", c->t);
  for (int i = 0; i < c->n_bodies; ++i)
    if (c->bodies[i].present) printf("state body %s %d moving %d\n", c->bodies[i].key, c->bodies[i].n, c->bodies[i].v[7] > 0.01);
  for (int i = 0; i < c->n_joints; ++i)
    if (c->joints[i].present) printf("state joint %s\n", c->joints[i].key);
  if (sb_reply(c, 1) != 0) return 1;
  printf("end\n");
  return 0;
}

int main(int argc, char** argv) {
  sb_client c;
  if (sb_connect(&c, 0, 30.0) != 0) {
    fprintf(stderr, "drive_two_wheel: %s\n", c.error);
    return 1;
  }
  if (argc > 1 && strcmp(argv[1], "probe") == 0) return probe(&c);
  const char* motion = c.motions[0].key;
  const char* body = c.bodies[0].key;
  int r, steps = 0;
  while ((r = sb_state(&c)) == 1) {
    const double* pose = sb_body(&c, body);
    double v[2] = {0.2, 0.0};
    if (c.t >= 2.0) {
      double w = 2.0 * (PI / 2 - heading(pose + 3));
      v[0] = 0.0;
      v[1] = w > 1.0 ? 1.0 : (w < -1.0 ? -1.0 : w);
    }
    sb_set(&c, motion, 2, v);
    if (sb_step(&c) != 0) break;
    ++steps;
  }
  if (r != 0) {
    fprintf(stderr, "drive_two_wheel: %s\n", c.error);
    return 1;
  }
  fprintf(stderr, "drive_two_wheel: the run ended at t=%g s after %d exchanges\n", c.end_time, steps);
  sb_close(&c);
  return 0;
}
