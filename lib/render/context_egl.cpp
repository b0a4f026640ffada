// EGL without a display: Mesa's surfaceless platform (llvmpipe here, a GPU's render node where
// there is one), else the device platform. No window, no pbuffer: the context renders into a
// framebuffer object.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include "render/gl_context.h"

namespace simbob::render {

namespace {

constexpr const char* kEglPackage = "libegl1 and libegl-mesa0 (Debian: apt-get install libegl1 libegl-mesa0)";

struct EglFns {
  PFNEGLGETPROCADDRESSPROC GetProcAddress = nullptr;
  PFNEGLINITIALIZEPROC Initialize = nullptr;
  PFNEGLTERMINATEPROC Terminate = nullptr;
  PFNEGLBINDAPIPROC BindAPI = nullptr;
  PFNEGLCHOOSECONFIGPROC ChooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC CreateContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC DestroyContext = nullptr;
  PFNEGLMAKECURRENTPROC MakeCurrent = nullptr;
  PFNEGLQUERYSTRINGPROC QueryString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplayEXT = nullptr;
  PFNEGLQUERYDEVICESEXTPROC QueryDevicesEXT = nullptr;
};

class EglContext : public GlContext {
 public:
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) egl_.DestroyContext(display_, context_);
    }
    // Neither the library nor the display is ever let go: Mesa registers exit handlers inside
    // libEGL, and eglTerminate unloads its driver, which the next context would load again.
    // eglGetPlatformDisplay hands every context the same display and eglInitialize of an
    // initialized display does nothing, so contexts still come and go freely.
  }
  std::string name() const override { return name_; }
  bool makeCurrent() override {
    return egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE;
  }
  void release() override { egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

  bool open(Error* err) {
    void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) return fail(err, ErrorKind::MissingInput, std::string("EGL is not installed: install ") + kEglPackage);
    egl_.GetProcAddress = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(lib, "eglGetProcAddress"));
    if (!egl_.GetProcAddress) return fail(err, ErrorKind::MissingInput, "libEGL.so.1 has no eglGetProcAddress");
    auto get = [&](const char* n) { return reinterpret_cast<void*>(egl_.GetProcAddress(n)); };
    egl_.Initialize = reinterpret_cast<PFNEGLINITIALIZEPROC>(get("eglInitialize"));
    egl_.Terminate = reinterpret_cast<PFNEGLTERMINATEPROC>(get("eglTerminate"));
    egl_.BindAPI = reinterpret_cast<PFNEGLBINDAPIPROC>(get("eglBindAPI"));
    egl_.ChooseConfig = reinterpret_cast<PFNEGLCHOOSECONFIGPROC>(get("eglChooseConfig"));
    egl_.CreateContext = reinterpret_cast<PFNEGLCREATECONTEXTPROC>(get("eglCreateContext"));
    egl_.DestroyContext = reinterpret_cast<PFNEGLDESTROYCONTEXTPROC>(get("eglDestroyContext"));
    egl_.MakeCurrent = reinterpret_cast<PFNEGLMAKECURRENTPROC>(get("eglMakeCurrent"));
    egl_.QueryString = reinterpret_cast<PFNEGLQUERYSTRINGPROC>(get("eglQueryString"));
    egl_.GetPlatformDisplayEXT = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(get("eglGetPlatformDisplayEXT"));
    egl_.QueryDevicesEXT = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(get("eglQueryDevicesEXT"));
    if (!egl_.Initialize || !egl_.BindAPI || !egl_.ChooseConfig || !egl_.CreateContext || !egl_.MakeCurrent ||
        !egl_.QueryString || !egl_.GetPlatformDisplayEXT)
      return fail(err, ErrorKind::MissingInput,
                  std::string("EGL lacks eglGetPlatformDisplayEXT or core calls: install ") + kEglPackage);
    // Surfaceless first: no display server, no device node needed.
    std::string why;
    if (tryDisplay(egl_.GetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), &why)) {
      name_ = "EGL (surfaceless)";
      return true;
    }
    std::string why_surfaceless = why;
    if (egl_.QueryDevicesEXT) {
      EGLDeviceEXT devices[16];
      EGLint n = 0;
      if (egl_.QueryDevicesEXT(16, devices, &n))
        for (EGLint i = 0; i < n; ++i)
          if (tryDisplay(egl_.GetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), &why)) {
            name_ = "EGL (device)";
            return true;
          }
    }
    return fail(err, ErrorKind::MissingInput,
                "EGL found no display without a window system (surfaceless: " + why_surfaceless + "; device: " + why +
                    "): install libegl-mesa0 and libgl1-mesa-dri");
  }

  bool makeTarget(int w, int h, Error* err) {
    std::string missing;
    if (!gl.load(egl_.GetProcAddress, true, &missing))
      return fail(err, ErrorKind::MissingInput, "EGL's GL lacks " + missing + ": install libgl1-mesa-dri");
    GLuint fbo = 0, color = 0, depth = 0;
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.GenRenderbuffers(1, &color);
    gl.BindRenderbuffer(GL_RENDERBUFFER, color);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    gl.GenRenderbuffers(1, &depth);
    gl.BindRenderbuffer(GL_RENDERBUFFER, depth);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return fail(err, ErrorKind::Internal,
                  "EGL: the " + std::to_string(w) + "x" + std::to_string(h) + " framebuffer is incomplete");
    return true;
  }

 private:
  bool tryDisplay(EGLDisplay d, std::string* why) {
    if (d == EGL_NO_DISPLAY) {
      *why = "no display";
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!egl_.Initialize(d, &major, &minor)) {
      *why = "eglInitialize failed";
      return false;
    }
    if (!egl_.BindAPI(EGL_OPENGL_API)) {
      *why = "no desktop OpenGL";
      egl_.Terminate(d);
      return false;
    }
    const EGLint attrs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = nullptr;
    EGLint n = 0;
    if (!egl_.ChooseConfig(d, attrs, &cfg, 1, &n) || n < 1) {
      *why = "no OpenGL config";
      egl_.Terminate(d);
      return false;
    }
    // Version 1.0 without a profile: the highest compatibility context (fixed-function GL).
    EGLContext ctx = egl_.CreateContext(d, cfg, EGL_NO_CONTEXT, nullptr);
    if (ctx == EGL_NO_CONTEXT) {
      *why = "eglCreateContext failed";
      egl_.Terminate(d);
      return false;
    }
    if (!egl_.MakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      *why = "no surfaceless context (EGL_KHR_surfaceless_context)";
      egl_.DestroyContext(d, ctx);
      egl_.Terminate(d);
      return false;
    }
    display_ = d;
    context_ = ctx;
    return true;
  }

  static bool fail(Error* err, ErrorKind kind, const std::string& msg) {
    err->kind = kind;
    err->message = msg;
    return false;
  }

  EglFns egl_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string name_;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(int width, int height, Error* err) {
  auto c = std::make_unique<EglContext>();
  if (!c->open(err) || !c->makeTarget(width, height, err)) return nullptr;
  return c;
}

std::unique_ptr<GlContext> createContext(GlBackend backend, int width, int height, Error* err) {
  switch (backend) {
    case GlBackend::Egl:
      return createEglContext(width, height, err);
    case GlBackend::OsMesa:
      return createOsMesaContext(width, height, err);
    case GlBackend::Auto: {
      Error egl_err;
      if (auto c = createEglContext(width, height, &egl_err)) return c;
      Error os_err;
      if (auto c = createOsMesaContext(width, height, &os_err)) return c;
      err->kind = ErrorKind::MissingInput;
      err->message = "no GL back end: " + egl_err.message + "; " + os_err.message;
      return nullptr;
    }
  }
  return nullptr;
}

}  // namespace simbob::render
