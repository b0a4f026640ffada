// The GL entry points the renderer calls, loaded at run time through the back end's
// GetProcAddress: simbob links no GL library, so OSMesa's and EGL's (glvnd's) copies of the
// same functions never clash, and a machine without them gets an error naming the package.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

#include <string>

namespace simbob::render {

// Fixed-function GL 1.x (both Mesa back ends give compatibility contexts) and the FBO calls.
// clang-format off
#define SIMBOB_GL_FUNCTIONS(X)                                                                  \
  X(Begin) X(End) X(Vertex3d) X(Normal3d) X(TexCoord2d) X(Color4d) X(Clear) X(ClearColor)       \
  X(ClearStencil) X(Enable) X(Disable) X(MatrixMode) X(LoadIdentity) X(LoadMatrixd)             \
  X(MultMatrixd) X(PushMatrix) X(PopMatrix) X(Frustum) X(Viewport) X(Lightfv) X(LightModelfv)   \
  X(LightModeli) X(Materialfv) X(Materialf) X(ShadeModel) X(PolygonMode) X(PolygonOffset)       \
  X(DepthFunc) X(DepthMask) X(BlendFunc) X(StencilFunc) X(StencilOp) X(Fogi) X(Fogf) X(Fogfv)   \
  X(Hint) X(GenTextures) X(DeleteTextures) X(BindTexture) X(TexImage2D) X(TexParameteri)        \
  X(TexEnvi) X(PixelStorei) X(ReadPixels) X(Finish) X(GetString) X(GetError) X(GetIntegerv)     \
  X(LineWidth) X(PointSize) X(ColorMask) X(ColorMaterial) X(FrontFace) X(CullFace)            \
  X(GenLists) X(NewList) X(EndList) X(CallList) X(DeleteLists)
// clang-format on

struct GlApi {
// NOLINTNEXTLINE(bugprone-macro-parentheses): `name` is a member name, not an expression
#define SIMBOB_GL_DECLARE(name) decltype(&::gl##name) name = nullptr;
  SIMBOB_GL_FUNCTIONS(SIMBOB_GL_DECLARE)
#undef SIMBOB_GL_DECLARE
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
  PFNGLGENRENDERBUFFERSPROC GenRenderbuffers = nullptr;
  PFNGLBINDRENDERBUFFERPROC BindRenderbuffer = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;

  /// Loads every entry point through `get`; false with the first missing name in *missing.
  /// `fbo`: the framebuffer-object calls too (EGL renders into an FBO; OSMesa into its buffer).
  template <class Get>
  bool load(Get get, bool fbo, std::string* missing) {
// `name` is a member name, not an expression: it cannot take parentheses.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define SIMBOB_GL_LOAD(name)                                \
  name = reinterpret_cast<decltype(name)>(get("gl" #name)); \
  if (!name) {                                              \
    *missing = "gl" #name;                                  \
    return false;                                           \
  }
    // NOLINTEND(bugprone-macro-parentheses)
    SIMBOB_GL_FUNCTIONS(SIMBOB_GL_LOAD)
    if (fbo) {
      SIMBOB_GL_LOAD(GenFramebuffers)
      SIMBOB_GL_LOAD(BindFramebuffer)
      SIMBOB_GL_LOAD(GenRenderbuffers)
      SIMBOB_GL_LOAD(BindRenderbuffer)
      SIMBOB_GL_LOAD(RenderbufferStorage)
      SIMBOB_GL_LOAD(FramebufferRenderbuffer)
      SIMBOB_GL_LOAD(CheckFramebufferStatus)
    }
#undef SIMBOB_GL_LOAD
    return true;
  }
};

/// A current GL context rendering off-screen into a width x height RGBA target with depth
/// and stencil.
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual std::string name() const = 0;
  /// Makes the context current on the calling thread (it must not be current on another one);
  /// false if the back end refuses.
  virtual bool makeCurrent() = 0;
  /// Makes no context current on the calling thread, so that another thread may take it.
  virtual void release() = 0;
  GlApi gl;
};

}  // namespace simbob::render
