/* The C peer of tests/cli/socket_camera.sh, through examples/clients/simbob_client.c: what
 * socket_camera_peer.py does, printing the same lines.
 *   socket_camera_peer PREFIX       subscribes to every camera after the first state and writes
 *                                   each image it receives to PREFIX_T.rgb (T with 2 decimals)
 *   socket_camera_peer PREFIX bad   subscribes to a camera that does not exist */
#include "simbob_client.c" /* first: it sets the POSIX feature macro */

static int images_present(const sb_client* c) {
  int n = 0;
  for (int i = 0; i < c->n_cameras; ++i) n += c->cameras[i].present;
  return n;
}

int main(int argc, char** argv) {
  static sb_client c; /* large: not on the stack */
  if (argc < 2) return 64;
  if (sb_connect(&c, 0, 30.0) != 0) {
    fprintf(stderr, "socket_camera_peer: %s\n", c.error);
    return 1;
  }
  printf("version %d\n", c.version);
  for (int i = 0; i < c.n_cameras; ++i)
    printf("camera %s %d %d %g\n", c.cameras[i].key, c.cameras[i].width, c.cameras[i].height, c.cameras[i].period);
  if (sb_state(&c) != 1) return 1;
  printf("t %.2f images %d\n", c.t, images_present(&c));
  if (argc > 2 && strcmp(argv[2], "bad") == 0) {
    const char* nose = "Bot.Nose";
    sb_subscribe(&c, "cameras", 1, &nose);
    if (sb_step(&c) == 0 && sb_state(&c) == -1) printf("error %s\n", c.error + strlen("simbob says: "));
    return 0;
  }
  sb_subscribe(&c, "cameras", -1, NULL);
  int r;
  if (sb_step(&c) != 0) return 1;
  while ((r = sb_state(&c)) == 1) {
    for (int i = 0; i < c.n_cameras; ++i) {
      int w, h;
      const unsigned char* rgb = sb_image_of(&c, c.cameras[i].key, &w, &h);
      if (!rgb) continue;
      printf("t %.2f image %s %d %d %zu\n", c.t, c.cameras[i].key, w, h, c.cameras[i].size);
      char name[512];
      snprintf(name, sizeof name, "%s_%.2f.rgb", argv[1], c.t);
      FILE* f = fopen(name, "wb");
      if (!f || fwrite(rgb, 1, c.cameras[i].size, f) != c.cameras[i].size || fclose(f) != 0) return 1;
    }
    if (sb_step(&c) != 0) return 1;
  }
  if (r != 0) {
    fprintf(stderr, "socket_camera_peer: %s\n", c.error);
    return 1;
  }
  printf("bye %g\n", c.end_time);
  sb_close(&c);
  return 0;
}
