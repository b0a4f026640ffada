// Deliberately wrong: physics code that reaches for GL. Expected not to build.
#include <GL/gl.h>

int strayGlUse() { return 0; }
