// Layer boundary (CMakeLists.txt): only the render layer may include GL headers.
#error "layer boundary: only lib/render may include GL headers (<GL/gl.h>)"
