// The render tests: one ctest per GL back end (SIMBOB_GL=egl or osmesa). A back end this
// machine does not have makes the run exit 77 (ctest: skipped) saying why, never pass.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>

#include "simbob/renderer.h"

int main(int argc, char** argv) {
  const char* gl = std::getenv("SIMBOB_GL");
  simbob::GlBackend b = simbob::GlBackend::Auto;
  if (!gl || !simbob::parseGlBackend(gl, &b)) {
    std::fprintf(stderr, "set SIMBOB_GL to egl or osmesa\n");
    return 2;
  }
  simbob::Model empty;
  empty.skins.push_back(simbob::SkinDef{});
  simbob::RenderOptions o;
  o.width = o.height = 8;
  o.backend = b;
  simbob::Error err;
  if (!simbob::Renderer::create(empty, o, &err)) {
    std::printf("skipped: GL back end '%s' unavailable: %s\n", gl, err.message.c_str());
    return 77;
  }
  return Catch::Session().run(argc, argv);
}
