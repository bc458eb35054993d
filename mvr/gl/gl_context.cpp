#include "mvr/gl/gl_context.h"

#include <cstdlib>
#include <string>
#include <thread>

#include "mvr/error.h"
#include "mvr/parallel.h"
#include "mvr/gl/gl_api.h"

namespace mvr {

GlPlatform parseGlPlatform(const std::string& name) {
  return parseName(kGlPlatformNames, name, "--gl", "platform");
}

const char* glPlatformName(GlPlatform platform) { return nameOf(kGlPlatformNames, platform); }

std::string GlContext::renderer() const {
  return reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
}

std::string GlContext::version() const {
  return reinterpret_cast<const char*>(gl::GetString(GL_VERSION));
}

std::string GlContext::describe() const {
  return std::string(glPlatformName(platform_)) + ": " + version() + " | " + renderer();
}

void GlContext::finishSetup() {
  GLint major = 0, minor = 0;
  gl::GetIntegerv(GL_MAJOR_VERSION, &major);
  gl::GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45)
    fail(glPlatformName(platform_), "GL " + std::to_string(major) + "." + std::to_string(minor) +
                                        " context, 4.5 core required");
}

std::unique_ptr<GlContext> GlContext::create(GlPlatform platform) {
  // llvmpipe starts a rasterizer thread per CPU of the machine, not of the
  // process: bound to fewer (taskset, mpirun's binding) its threads take
  // turns on them, 4x slower on one core of two (svr, 143K teacup).
  if (const int cores = availableCores(); cores < int(std::thread::hardware_concurrency()))
    setenv("LP_NUM_THREADS", std::to_string(cores).c_str(), 0);
  switch (platform) {
    case GlPlatform::Egl: return createEglContext();
    case GlPlatform::OsMesa: return createOsMesaContext();
    case GlPlatform::Glfw: return createGlfwContext(64, 64, false);
    case GlPlatform::Auto: break;
  }
  std::string eglProblem;
  try {
    return createEglContext();
  } catch (const Error& e) {
    eglProblem = e.what();
  }
  try {
    return createOsMesaContext();
  } catch (const Error& e) {
    fail("GL", std::string("no headless context (") + eglProblem + "; " + e.what() + ")");
  }
}

}  // namespace mvr
