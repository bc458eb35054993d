// OSMesa: pure software GL, loaded with dlopen so that its exported gl*
// symbols never interpose on the libGL that GLFW or EGL bring.
#include <dlfcn.h>

#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/gl/gl_context.h"

namespace mvr {
namespace {

// From GL/osmesa.h, which cannot be included beside GL/glcorearb.h.
using OSMesaContext = struct osmesa_context*;
using OSMESAproc = void (*)();
constexpr int OSMESA_RGBA = GL_RGBA;
constexpr int OSMESA_FORMAT = 0x22;
constexpr int OSMESA_DEPTH_BITS = 0x30;
constexpr int OSMESA_PROFILE = 0x33;
constexpr int OSMESA_CORE_PROFILE = 0x34;
constexpr int OSMESA_CONTEXT_MAJOR_VERSION = 0x36;
constexpr int OSMESA_CONTEXT_MINOR_VERSION = 0x37;

struct OsMesaApi {
  void* library = nullptr;
  OSMesaContext (*createContextAttribs)(const int*, OSMesaContext) = nullptr;
  GLboolean (*makeCurrent)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  void (*destroyContext)(OSMesaContext) = nullptr;
  OSMESAproc (*getProcAddress)(const char*) = nullptr;
};

const OsMesaApi& osMesa() {
  static OsMesaApi api = [] {
    OsMesaApi a;
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
      a.library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (a.library) break;
    }
    if (!a.library) return a;
    a.createContextAttribs = reinterpret_cast<decltype(a.createContextAttribs)>(
        dlsym(a.library, "OSMesaCreateContextAttribs"));
    a.makeCurrent = reinterpret_cast<decltype(a.makeCurrent)>(dlsym(a.library, "OSMesaMakeCurrent"));
    a.destroyContext =
        reinterpret_cast<decltype(a.destroyContext)>(dlsym(a.library, "OSMesaDestroyContext"));
    a.getProcAddress =
        reinterpret_cast<decltype(a.getProcAddress)>(dlsym(a.library, "OSMesaGetProcAddress"));
    return a;
  }();
  return api;
}

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(OSMesaContext ctx) : GlContext(GlPlatform::OsMesa), ctx_(ctx) {}
  ~OsMesaContext() override { osMesa().destroyContext(ctx_); }
  void setup() { finishSetup(); }
  // OSMesa insists on a colour buffer; rendering goes to FBOs, so 1x1.
  std::vector<unsigned char> buffer = std::vector<unsigned char>(4);

 private:
  OSMesaContext ctx_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() {
  const OsMesaApi& api = osMesa();
  if (!api.library) fail("osmesa", "libOSMesa.so.8 not found (apt-get install libosmesa6)");
  if (!api.createContextAttribs || !api.makeCurrent || !api.getProcAddress)
    fail("osmesa", "libOSMesa lacks OSMesaCreateContextAttribs");
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                         OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
  OSMesaContext ctx = api.createContextAttribs(attribs, nullptr);
  if (!ctx) fail("osmesa", "cannot create a GL 4.5 core context");
  auto context = std::make_unique<OsMesaContext>(ctx);
  if (!api.makeCurrent(ctx, context->buffer.data(), GL_UNSIGNED_BYTE, 1, 1))
    fail("osmesa", "OSMesaMakeCurrent failed");
  static OSMESAproc (*getProc)(const char*) = api.getProcAddress;
  gl::loadFunctions([](const char* n) { return reinterpret_cast<void*>(getProc(n)); });
  context->setup();
  return context;
}

}  // namespace mvr
