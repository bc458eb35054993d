// EGL contexts: the NVIDIA (or any hardware) device platform when present,
// else Mesa's surfaceless platform (llvmpipe on machines without a GPU).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/gl/gl_context.h"

namespace mvr {
namespace {

template <class Fn>
Fn eglProc(const char* name) {
  return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

bool contains(const char* list, const char* word) {
  if (!list) return false;
  size_t n = std::strlen(word);
  for (const char* p = std::strstr(list, word); p; p = std::strstr(p + 1, word))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

// Displays to try, best first: hardware devices, then surfaceless.
std::vector<EGLDisplay> candidateDisplays() {
  std::vector<EGLDisplay> out;
  auto getPlatformDisplay = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  auto queryDevices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto queryDeviceString = eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  if (!getPlatformDisplay) return out;
  if (queryDevices && queryDeviceString) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        const char* ext = queryDeviceString(devices[i], EGL_EXTENSIONS);
        if (contains(ext, "EGL_MESA_device_software")) continue;
        EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back(d);
      }
    }
  }
  EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (d != EGL_NO_DISPLAY) out.push_back(d);
  return out;
}

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, EGLContext context)
      : GlContext(GlPlatform::Egl), display_(display), context_(context) {}
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // eglTerminate is left out on purpose: displays are shared per process
    // and terminating one under NVIDIA's driver invalidates later contexts.
  }
  void setup() { finishSetup(); }

 private:
  EGLDisplay display_;
  EGLContext context_;
};

EGLContext tryContext(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return EGL_NO_CONTEXT;
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  const char* ext = eglQueryString(display, EGL_EXTENSIONS);
  if (!contains(ext, "EGL_KHR_surfaceless_context")) return EGL_NO_CONTEXT;
  EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR
  if (!contains(ext, "EGL_KHR_no_config_context")) {
    const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1) return EGL_NO_CONTEXT;
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT) return ctx;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(display, ctx);
    return EGL_NO_CONTEXT;
  }
  return ctx;
}

}  // namespace

std::unique_ptr<GlContext> createEglContext() {
  for (EGLDisplay display : candidateDisplays()) {
    EGLContext ctx = tryContext(display);
    if (ctx == EGL_NO_CONTEXT) continue;
    gl::loadFunctions([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); });
    auto context = std::make_unique<EglContext>(display, ctx);
    context->setup();
    return context;
  }
  fail("egl", "no EGL display gives a surfaceless GL 4.5 core context");
}

}  // namespace mvr
