// The two back ends behind one interface: EGL without a display and OSMesa. Both are opened
// with dlopen, so simbob starts on machines without them and says what to install.
#pragma once

#include <memory>

#include "render/gl_api.h"
#include "simbob/error.h"
#include "simbob/renderer.h"

namespace simbob::render {

/// EGL: the surfaceless platform (EGL_MESA_platform_surfaceless), then the device platform
/// (EGL_EXT_platform_device); desktop GL (eglBindAPI(EGL_OPENGL_API)) into an FBO.
std::unique_ptr<GlContext> createEglContext(int width, int height, Error* err);
/// OSMesa: renders into a buffer of its own (Mesa's software rasterizer).
std::unique_ptr<GlContext> createOsMesaContext(int width, int height, Error* err);
/// The back end asked for; Auto tries EGL, then OSMesa (the error names both when neither works).
std::unique_ptr<GlContext> createContext(GlBackend backend, int width, int height, Error* err);

}  // namespace simbob::render
