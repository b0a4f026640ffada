/* The left-wall follower of scenes/maze_socket.xml in C, through simbob_client.c: the program of
 * maze_follower.py (its docstring has the law), with the same float64 operations in the same
 * order -- min and clamp written as Python's min() and max() evaluate them, cos from the C
 * library as Python's math.cos -- so both send the same commands and drive the robot to the same
 * trajectory bytes (tests/cli/clients.sh).
 *   cc -std=c99 -O2 -ffp-contract=off -o maze_follower maze_follower.c -lm
 *   simbob run scenes/maze_socket.xml --duration 60 --controller Bot.Cart.Link=./maze_follower */
#include "simbob_client.c" /* first: it sets the POSIX feature macro */

#include <math.h>

#define PI 3.141592653589793 /* Python's math.pi */
#define DISTANCE 0.25        /* m from the wall on the left */
#define SPEED 0.2            /* m/s */
#define TURN 2.0             /* rad/s */

/* Python's min(a, b) and max(lo, min(hi, x)), zero signs included. */
static double py_min(double a, double b) { return b < a ? b : a; }
static double py_clamp(double x, double lo, double hi) {
  double m = py_min(hi, x);
  return m > lo ? m : lo;
}

typedef struct {
  double period, last_e;
  int first, n_side, n_front;
  int side[SB_VALUES], front[SB_VALUES];
  double front_cos[SB_VALUES];
} follower;

static void follower_init(follower* f, int n, double period) {
  memset(f, 0, sizeof *f);
  f->period = period;
  f->first = 1;
  for (int k = 0; k < n; ++k) { /* bearing of ray k in degrees times n: k 360 - 180 n */
    int b = k * 360 - 180 * n;
    if (45 * n <= b && b <= 170 * n) f->side[f->n_side++] = k;
    if (abs(b) < 25 * n) {
      f->front_cos[f->n_front] = cos((double)b * PI / (double)(180 * n));
      f->front[f->n_front++] = k;
    }
  }
}

static void follower_command(follower* f, const double* r, double* v) {
  double d = INFINITY, g = INFINITY;
  for (int i = 0; i < f->n_side; ++i) d = py_min(d, r[f->side[i]]);
  for (int i = 0; i < f->n_front; ++i) g = py_min(g, r[f->front[i]] * f->front_cos[i]);
  double e = d - DISTANCE;
  double de = f->first ? 0.0 : py_clamp((e - f->last_e) / f->period, -SPEED, SPEED);
  f->first = 0;
  f->last_e = e;
  if (g < 1.5 * DISTANCE) {
    v[0] = SPEED * py_clamp((g - DISTANCE) / DISTANCE, 0.0, 1.0);
    v[1] = -TURN;
    return;
  }
  double wn = 2.0 * SPEED / DISTANCE;
  v[0] = SPEED;
  v[1] = py_clamp(wn * wn / SPEED * e + 2.0 * wn / SPEED * de, -TURN, TURN);
}

int main(void) {
  static sb_client c; /* large: not on the stack */
  if (sb_connect(&c, 0, 30.0) != 0) {
    fprintf(stderr, "maze_follower: %s\n", c.error);
    return 1;
  }
  const char* scanner = NULL;
  int n = 0;
  for (int i = 0; i < c.n_sensors && !scanner; ++i)
    if (strcmp(c.sensors[i].kind, "scanner") == 0) {
      scanner = c.sensors[i].key;
      n = c.sensors[i].n;
    }
  if (!scanner || c.n_motions == 0 || n > SB_VALUES) {
    fprintf(stderr, "maze_follower: no scanner (of at most %d rays) or no motion control\n", SB_VALUES);
    return 1;
  }
  const char* motion = c.motions[0].key;
  follower f;
  follower_init(&f, n, c.period);
  int r, steps = 0;
  while ((r = sb_state(&c)) == 1) {
    int got = 0;
    const double* ranges = sb_sensor(&c, scanner, &got);
    if (!ranges || got != n) {
      fprintf(stderr, "maze_follower: no scan at t=%g\n", c.t);
      return 1;
    }
    double v[2];
    follower_command(&f, ranges, v);
    sb_set(&c, motion, 2, v);
    if (steps == 0) { /* the scanner only, from the next exchange on */
      sb_subscribe(&c, "bodies", 0, NULL);
      sb_subscribe(&c, "joints", 0, NULL);
      sb_subscribe(&c, "sensors", 1, &scanner);
    }
    if (sb_step(&c) != 0) break;
    ++steps;
  }
  if (r != 0) {
    fprintf(stderr, "maze_follower: %s\n", c.error);
    return 1;
  }
  fprintf(stderr, "maze_follower: the run ended at t=%g s after %d exchanges\n", c.end_time, steps);
  sb_close(&c);
  return 0;
}
