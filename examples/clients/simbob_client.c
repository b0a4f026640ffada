/* A single-file C client of simbob's socket protocol (docs/socket-protocol.md), versions 2 and 3.
 * C99 + POSIX sockets, no other dependency. Include it in one .c file of your program:
 *
 *     #include "simbob_client.c"
 *     sb_client c;
 *     if (sb_connect(&c, 0, 30.0) != 0) { fprintf(stderr, "%s\n", c.error); return 1; }
 *     while (sb_state(&c) == 1) {              // 1: a state; 0: simbob said 'bye'; -1: error
 *       const double *pose = sb_body(&c, "Bot.Cart.Chassis");
 *       double v[2] = {0.2, 0.0};
 *       sb_set(&c, "Bot.Motion", 2, v);        // buffered ...
 *       sb_step(&c);                           // ... and sent in one write with 'step'
 *     }
 *
 * sb_connect negotiates the newest version both sides speak (3); keys are unescaped on reading
 * and escaped on writing (%XX), so they are plain C strings (UTF-8) here. Numbers are written with
 * %.17g, which reads back to the same double. Errors: -1 with the reason in c.error (simbob's
 * 'error MESSAGE' included). Limits: SB_MAX entries of each kind, SB_VALUES numbers a line,
 * SB_CAMERAS camera sensors. Camera images (version 3, after sb_subscribe(c, "cameras", ...)):
 * sb_image_of; their bytes live in buffers this file allocates and sb_close frees. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* clock_gettime, nanosleep */
#endif
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

/* Limits; define any of them before the #include to change it (a scanner of 360 rays needs
 * SB_VALUES 360 or more). simbob's lines have no length limit: one carries a whole scanner. A
 * state line beyond SB_VALUES numbers or SB_LINE bytes is an error (-1), never cut short. */
#ifndef SB_MAX
#define SB_MAX 256 /* bodies, joints, sensors, actuators, motions */
#endif
#ifndef SB_KEY
#define SB_KEY 256 /* bytes of a key, its terminating 0 included */
#endif
#ifndef SB_VALUES
#define SB_VALUES 64 /* numbers on one state line */
#endif
#ifndef SB_LINE
#define SB_LINE (SB_VALUES * 25 + 3 * SB_KEY + 64) /* a line and its 0: room for SB_VALUES numbers */
#endif
#ifndef SB_CAMERAS
#define SB_CAMERAS 16 /* camera sensors */
#endif

typedef struct {
  char key[SB_KEY];
  char kind[32]; /* actuator: voltage|position|velocity; joint: hinge|...; sensor: proximity|... */
  int n;         /* values a state line carries (joint 2; sensor N; body 7 or 13) */
  double v[SB_VALUES];
  int present; /* in the last state block (subscriptions leave some out) */
} sb_entry;

typedef struct {
  char key[SB_KEY];
  int width, height;  /* pixels, from the hello */
  double period;      /* s between images */
  unsigned char* rgb; /* the last image: RGB, rows top first, 3 bytes a pixel (malloc'd) */
  size_t size, cap;   /* bytes in rgb; bytes allocated */
  int present;        /* in the last state block (only cameras subscribed to are) */
} sb_image;

typedef struct {
  int fd;
  char in[SB_LINE > (1 << 16) ? SB_LINE : (1 << 16)];
  size_t len;
  int version;
  int offered[8], n_offered;
  char key[SB_KEY];
  double period, t, end_time;
  sb_entry actuators[SB_MAX], motions[SB_MAX], joints[SB_MAX], sensors[SB_MAX], bodies[SB_MAX];
  int n_actuators, n_motions, n_joints, n_sensors, n_bodies;
  sb_image cameras[SB_CAMERAS];
  int n_cameras;
  int first_pending; /* the state block read while connecting has not been returned yet */
  char line[SB_LINE]; /* the line being read */
  char out[1 << 16];
  size_t out_len;
  char error[SB_LINE + 64];
} sb_client;

static inline int sb_fail(sb_client* c, const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(c->error, sizeof c->error, fmt, ap);
  va_end(ap);
  return -1;
}

/* Escapes `key` into out (a word of the protocol). */
static inline void sb_escape(const char* key, char* out, size_t cap) {
  static const char hex[] = "0123456789ABCDEF";
  size_t o = 0;
  for (const unsigned char* p = (const unsigned char*)key; *p && o + 4 < cap; ++p) {
    if (*p <= 0x20 || *p >= 0x7f || *p == '%' || *p == ',') {
      out[o++] = '%';
      out[o++] = hex[*p >> 4];
      out[o++] = hex[*p & 15];
    } else {
      out[o++] = (char)*p;
    }
  }
  out[o] = 0;
}

static inline int sb_hex(char ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  return -1;
}

static inline void sb_unescape(const char* word, char* out, size_t cap) {
  size_t o = 0;
  for (size_t i = 0; word[i] && o + 1 < cap; ++i) {
    if (word[i] == '%' && sb_hex(word[i + 1]) >= 0 && sb_hex(word[i + 2]) >= 0) {
      out[o++] = (char)(sb_hex(word[i + 1]) * 16 + sb_hex(word[i + 2]));
      i += 2;
    } else {
      out[o++] = word[i];
    }
  }
  out[o] = 0;
}

/* Reads one line (without \n, \r) into line; -1 at end of file or error. */
static inline int sb_line(sb_client* c, char* line) {
  for (;;) {
    char* nl = memchr(c->in, '\n', c->len);
    if (nl) {
      size_t n = (size_t)(nl - c->in);
      if (n >= SB_LINE) return sb_fail(c, "simbob sent a line longer than %d bytes (define SB_LINE larger)", SB_LINE - 1);
      memcpy(line, c->in, n);
      line[n] = 0;
      if (n > 0 && line[n - 1] == '\r') line[n - 1] = 0;
      memmove(c->in, nl + 1, c->len - n - 1);
      c->len -= n + 1;
      return 0;
    }
    if (c->len == sizeof c->in) return sb_fail(c, "simbob sent a line longer than %d bytes (define SB_LINE larger)", (int)sizeof c->in);
    ssize_t r = recv(c->fd, c->in + c->len, sizeof c->in - c->len, 0);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return sb_fail(c, "simbob closed the connection");
    c->len += (size_t)r;
  }
}

/* Splits line in place into at most max words. */
static inline int sb_words(char* line, char** w, int max) {
  int n = 0;
  for (char* p = line; *p && n < max;) {
    while (*p == ' ' || *p == '\t') *p++ = 0;
    if (!*p) break;
    w[n++] = p;
    while (*p && *p != ' ' && *p != '\t') ++p;
  }
  return n;
}

/* Reads exactly n bytes (an image's block) into out; out NULL: reads and drops them. */
static inline int sb_bytes(sb_client* c, unsigned char* out, size_t n) {
  while (n > 0) {
    if (c->len == 0) {
      ssize_t r = recv(c->fd, c->in, sizeof c->in, 0);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) return sb_fail(c, "simbob closed the connection");
      c->len = (size_t)r;
    }
    size_t k = n < c->len ? n : c->len;
    if (out) {
      memcpy(out, c->in, k);
      out += k;
    }
    memmove(c->in, c->in + k, c->len - k);
    c->len -= k;
    n -= k;
  }
  return 0;
}

static inline int sb_send(sb_client* c, const char* text, size_t n) {
  while (n > 0) {
    ssize_t r = send(c->fd, text, n, MSG_NOSIGNAL);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return sb_fail(c, "cannot send to simbob: %s", strerror(errno));
    text += r;
    n -= (size_t)r;
  }
  return 0;
}

static inline sb_entry* sb_find(sb_entry* list, int n, const char* key) {
  for (int i = 0; i < n; ++i)
    if (strcmp(list[i].key, key) == 0) return &list[i];
  return NULL;
}

static inline void sb_add(sb_entry* list, int* n, const char* word, const char* kind, int values) {
  if (*n >= SB_MAX) return;
  sb_entry* e = &list[(*n)++];
  memset(e, 0, sizeof *e);
  sb_unescape(word, e->key, sizeof e->key);
  snprintf(e->kind, sizeof e->kind, "%s", kind);
  e->n = values;
}

static inline int sb_hello(sb_client* c) {
  char* line = c->line;
  char* w[8];
  if (sb_line(c, line) != 0) return -1;
  int n = sb_words(line, w, 8);
  if (n < 4 || strcmp(w[0], "simbob") != 0) return sb_fail(c, "not a simbob hello");
  c->version = atoi(w[1]);
  sb_unescape(w[2], c->key, sizeof c->key);
  c->period = strtod(w[3], NULL);
  c->n_offered = 1;
  c->offered[0] = c->version;
  c->n_actuators = c->n_motions = c->n_joints = c->n_sensors = c->n_bodies = 0;
  for (int i = 0; i < c->n_cameras; ++i) free(c->cameras[i].rgb);
  c->n_cameras = 0;
  for (;;) {
    if (sb_line(c, line) != 0) return -1;
    n = sb_words(line, w, 8);
    if (n == 1 && strcmp(w[0], "end") == 0) return 0;
    if (n < 2) continue; /* a line this client does not know */
    if (strcmp(w[0], "versions") == 0) {
      c->n_offered = 0;
      for (int i = 1; i < n && c->n_offered < 8; ++i) c->offered[c->n_offered++] = atoi(w[i]);
    } else if (strcmp(w[0], "actuator") == 0 && n >= 3) {
      sb_add(c->actuators, &c->n_actuators, w[1], w[2], 1);
    } else if (strcmp(w[0], "motion") == 0) {
      sb_add(c->motions, &c->n_motions, w[1], "motion", 2);
    } else if (strcmp(w[0], "joint") == 0 && n >= 3) {
      sb_add(c->joints, &c->n_joints, w[1], w[2], 2);
    } else if (strcmp(w[0], "sensor") == 0) {
      sb_add(c->sensors, &c->n_sensors, w[1], n >= 4 ? w[2] : "proximity", n >= 4 ? atoi(w[3]) : 1);
    } else if (strcmp(w[0], "body") == 0) {
      sb_add(c->bodies, &c->n_bodies, w[1], "body", c->version >= 3 ? 13 : 7);
    } else if (strcmp(w[0], "camera") == 0 && n >= 5 && c->n_cameras < SB_CAMERAS) {
      sb_image* im = &c->cameras[c->n_cameras++];
      memset(im, 0, sizeof *im);
      sb_unescape(w[1], im->key, sizeof im->key);
      im->width = atoi(w[2]);
      im->height = atoi(w[3]);
      im->period = strtod(w[4], NULL);
    }
  }
}

static inline int sb_read_state(sb_client* c) {
  char* line = c->line;
  char key[SB_KEY];
  char* w[SB_VALUES + 3];
  int n;
  for (;;) { /* up to 't' */
    if (sb_line(c, line) != 0) return -1;
    if (strncmp(line, "error ", 6) == 0) return sb_fail(c, "simbob says: %s", line + 6);
    n = sb_words(line, w, SB_VALUES + 3);
    if (n >= 2 && strcmp(w[0], "bye") == 0) {
      c->end_time = strtod(w[1], NULL);
      return 0;
    }
    if (n >= 2 && strcmp(w[0], "t") == 0) break;
  }
  c->t = strtod(w[1], NULL);
  sb_entry* lists[3] = {c->joints, c->sensors, c->bodies};
  int counts[3] = {c->n_joints, c->n_sensors, c->n_bodies};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < counts[k]; ++i) lists[k][i].present = 0;
  for (int i = 0; i < c->n_cameras; ++i) c->cameras[i].present = 0;
  for (;;) {
    if (sb_line(c, line) != 0) return -1;
    n = sb_words(line, w, SB_VALUES + 3);
    if (n == 1 && strcmp(w[0], "end") == 0) return 1;
    if (n > SB_VALUES + 2) return sb_fail(c, "a '%s' line with more than %d numbers (define SB_VALUES larger)", w[0], SB_VALUES);
    if (n < 2) continue;
    sb_unescape(w[1], key, sizeof key);
    if (strcmp(w[0], "image") == 0 && n >= 5) { /* N bytes of RGB follow the line */
      size_t size = (size_t)strtoull(w[4], NULL, 10);
      sb_image* im = NULL;
      for (int i = 0; i < c->n_cameras; ++i)
        if (strcmp(c->cameras[i].key, key) == 0) im = &c->cameras[i];
      if (im && size > im->cap) {
        unsigned char* grown = (unsigned char*)realloc(im->rgb, size);
        if (!grown) return sb_fail(c, "no memory for an image of %zu bytes", size);
        im->rgb = grown;
        im->cap = size;
      }
      if (sb_bytes(c, im ? im->rgb : NULL, size) != 0) return -1;
      if (im) {
        im->width = atoi(w[2]);
        im->height = atoi(w[3]);
        im->size = size;
        im->present = 1;
      }
      continue;
    }
    sb_entry* e = NULL;
    if (strcmp(w[0], "joint") == 0) e = sb_find(c->joints, c->n_joints, key);
    if (strcmp(w[0], "sensor") == 0) e = sb_find(c->sensors, c->n_sensors, key);
    if (strcmp(w[0], "body") == 0) e = sb_find(c->bodies, c->n_bodies, key);
    if (!e) continue;
    e->n = n - 2;
    for (int i = 2; i < n; ++i) e->v[i - 2] = strtod(w[i], NULL);
    e->present = 1;
  }
}

/* Connects to simbob on 127.0.0.1:port (0: $SIMBOB_PORT), retrying for `wait` s while it starts,
 * reads the hello and the first state, and negotiates the newest version (max_version: 3, or 2
 * to stay at version 2). 0 on success. */
static inline int sb_connect_version(sb_client* c, int port, double wait, int max_version) {
  memset(c, 0, sizeof *c);
  c->fd = -1;
  if (port <= 0) {
    const char* env = getenv("SIMBOB_PORT");
    if (!env) return sb_fail(c, "no port given and SIMBOB_PORT is not set");
    port = atoi(env);
  }
  struct sockaddr_in a;
  memset(&a, 0, sizeof a);
  a.sin_family = AF_INET;
  a.sin_port = htons((unsigned short)port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  struct timespec start, now, pause = {0, 50000000};
  clock_gettime(CLOCK_MONOTONIC, &start);
  for (;;) {
    c->fd = socket(AF_INET, SOCK_STREAM, 0);
    if (c->fd < 0) return sb_fail(c, "cannot create a socket: %s", strerror(errno));
    if (connect(c->fd, (struct sockaddr*)&a, sizeof a) == 0) break;
    int err = errno;
    close(c->fd);
    c->fd = -1;
    clock_gettime(CLOCK_MONOTONIC, &now);
    double waited = (double)(now.tv_sec - start.tv_sec) + (double)(now.tv_nsec - start.tv_nsec) * 1e-9;
    if (err != ECONNREFUSED || waited > wait) return sb_fail(c, "cannot connect to port %d: %s", port, strerror(err));
    nanosleep(&pause, NULL);
  }
  int one = 1;
  setsockopt(c->fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  if (sb_hello(c) != 0 || sb_read_state(c) != 1) return -1;
  int chosen = c->version;
  for (int i = 0; i < c->n_offered; ++i)
    if (c->offered[i] > chosen && c->offered[i] <= max_version) chosen = c->offered[i];
  if (chosen > c->version) {
    char text[64];
    char* line = c->line;
    int n = snprintf(text, sizeof text, "version %d\n", chosen);
    if (sb_send(c, text, (size_t)n) != 0) return -1;
    for (;;) { /* simbob's answer comes after the rest of what it had sent */
      if (sb_line(c, line) != 0) return -1;
      if (strncmp(line, "version ", 8) == 0) break;
      if (strncmp(line, "error ", 6) == 0) return sb_fail(c, "simbob says: %s", line + 6);
    }
    if (sb_hello(c) != 0 || sb_read_state(c) != 1) return -1;
  }
  c->first_pending = 1;
  return 0;
}

static inline int sb_connect(sb_client* c, int port, double wait) { return sb_connect_version(c, port, wait, 3); }

/* The next state: 1 (c->t and the entries' values), 0 once simbob said 'bye' (c->end_time), -1. */
static inline int sb_state(sb_client* c) {
  if (c->first_pending) {
    c->first_pending = 0;
    return 1;
  }
  return sb_read_state(c);
}

/* The values of the body (joint, sensor) with this key in the last state, or NULL. */
static inline const double* sb_body(sb_client* c, const char* key) {
  sb_entry* e = sb_find(c->bodies, c->n_bodies, key);
  return e && e->present ? e->v : NULL;
}
static inline const double* sb_joint(sb_client* c, const char* key) {
  sb_entry* e = sb_find(c->joints, c->n_joints, key);
  return e && e->present ? e->v : NULL;
}
static inline const double* sb_sensor(sb_client* c, const char* key, int* n) {
  sb_entry* e = sb_find(c->sensors, c->n_sensors, key);
  if (n) *n = e ? e->n : 0;
  return e && e->present ? e->v : NULL;
}

/* The last image of the camera sensor with this key (width, height, RGB bytes rows top first), or
 * NULL when the last state block had none (subscribe to it first: sb_subscribe "cameras"). */
static inline const unsigned char* sb_image_of(sb_client* c, const char* key, int* width, int* height) {
  for (int i = 0; i < c->n_cameras; ++i) {
    sb_image* im = &c->cameras[i];
    if (strcmp(im->key, key) != 0 || !im->present) continue;
    if (width) *width = im->width;
    if (height) *height = im->height;
    return im->rgb;
  }
  return NULL;
}

static inline void sb_append(sb_client* c, const char* text) {
  size_t n = strlen(text);
  if (c->out_len + n < sizeof c->out) {
    memcpy(c->out + c->out_len, text, n);
    c->out_len += n;
  }
}

/* Buffers 'set KEY V1 ... Vn' for the next sb_step. */
static inline void sb_set(sb_client* c, const char* key, int n, const double* v) {
  char word[3 * SB_KEY], num[40];
  sb_escape(key, word, sizeof word);
  sb_append(c, "set ");
  sb_append(c, word);
  for (int i = 0; i < n; ++i) {
    snprintf(num, sizeof num, " %.17g", v[i]);
    sb_append(c, num);
  }
  sb_append(c, "\n");
}

/* Buffers 'subscribe KIND KEY...' (version 3; kind "bodies", "joints", "sensors" or "cameras";
 * n = -1: all). */
static inline void sb_subscribe(sb_client* c, const char* kind, int n, const char* const* keys) {
  char word[3 * SB_KEY];
  sb_append(c, "subscribe ");
  sb_append(c, kind);
  if (n < 0) sb_append(c, " *");
  for (int i = 0; i < n; ++i) {
    sb_escape(keys[i], word, sizeof word);
    sb_append(c, " ");
    sb_append(c, word);
  }
  sb_append(c, "\n");
}

/* Sends what was buffered and 'step' ('done' if done) in one write. 0 or -1. */
static inline int sb_reply(sb_client* c, int done) {
  sb_append(c, done ? "done\n" : "step\n");
  int r = sb_send(c, c->out, c->out_len);
  c->out_len = 0;
  return r;
}
static inline int sb_step(sb_client* c) { return sb_reply(c, 0); }

static inline void sb_close(sb_client* c) {
  if (c->fd >= 0) close(c->fd);
  c->fd = -1;
  for (int i = 0; i < c->n_cameras; ++i) {
    free(c->cameras[i].rgb);
    c->cameras[i].rgb = NULL;
    c->cameras[i].cap = c->cameras[i].size = 0;
  }
}
