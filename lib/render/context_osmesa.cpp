// OSMesa: Mesa's off-screen context rendering into a buffer of ours (Debian 12's Mesa 22.3;
// Mesa dropped OSMesa in 25.1, so EGL is the default).
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <vector>

#include "render/gl_context.h"

namespace simbob::render {

namespace {

constexpr const char* kOsMesaPackage = "libosmesa6 (Debian: apt-get install libosmesa6)";

using CreateExtFn = OSMesaContext (*)(GLenum, GLint, GLint, GLint, OSMesaContext);
using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using DestroyFn = void (*)(OSMesaContext);
using GetProcFn = OSMESAproc (*)(const char*);

class OsMesaContextImpl : public GlContext {
 public:
  ~OsMesaContextImpl() override {
    if (ctx_) destroy_(ctx_);
  }
  std::string name() const override { return "OSMesa"; }
  bool makeCurrent() override {
    return make_current_(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_) == GL_TRUE;
  }
  void release() override { make_current_(nullptr, nullptr, 0, 0, 0); }

  bool open(int w, int h, Error* err) {
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libOSMesa.so.6", RTLD_NOW | RTLD_LOCAL);
    if (!lib) return fail(err, std::string("OSMesa is not installed: install ") + kOsMesaPackage);
    auto create = reinterpret_cast<CreateExtFn>(dlsym(lib, "OSMesaCreateContextExt"));
    make_current_ = reinterpret_cast<MakeCurrentFn>(dlsym(lib, "OSMesaMakeCurrent"));
    destroy_ = reinterpret_cast<DestroyFn>(dlsym(lib, "OSMesaDestroyContext"));
    auto get_proc = reinterpret_cast<GetProcFn>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!create || !make_current_ || !destroy_ || !get_proc)
      return fail(err, std::string("libOSMesa lacks OSMesaCreateContextExt: install ") + kOsMesaPackage);
    ctx_ = create(OSMESA_RGBA, 24, 8, 0, nullptr);
    if (!ctx_) return fail(err, "OSMesaCreateContextExt failed");
    buffer_.assign(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 0);
    width_ = w;
    height_ = h;
    if (!makeCurrent()) return fail(err, "OSMesaMakeCurrent failed");
    std::string missing;
    if (!gl.load([&](const char* n) { return reinterpret_cast<void*>(get_proc(n)); }, false, &missing))
      return fail(err, "OSMesa lacks " + missing);
    return true;
  }

 private:
  static bool fail(Error* err, const std::string& msg) {
    err->kind = ErrorKind::MissingInput;
    err->message = msg;
    return false;
  }

  OSMesaContext ctx_ = nullptr;
  DestroyFn destroy_ = nullptr;
  MakeCurrentFn make_current_ = nullptr;
  int width_ = 0, height_ = 0;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext(int width, int height, Error* err) {
  auto c = std::make_unique<OsMesaContextImpl>();
  if (!c->open(width, height, err)) return nullptr;
  return c;
}

}  // namespace simbob::render
