// GLFW windows: the interactive viewer's context, or a hidden window.
#include "mvr/gl_api.h"  // before GLFW: glcorearb.h must come first

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "mvr/error.h"
#include "mvr/gl_context.h"

namespace mvr {
namespace {

class GlfwContext final : public GlContext {
 public:
  explicit GlfwContext(GLFWwindow* window) : GlContext(GlPlatform::Glfw), window_(window) {}
  ~GlfwContext() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  void setup() { finishSetup(); }

 private:
  GLFWwindow* window_;
};

}  // namespace

std::unique_ptr<GlContext> createGlfwContext(int width, int height, bool visible) {
  if (!glfwInit()) fail("glfw", "cannot initialise (no display? set DISPLAY or use --gl egl)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width, height, "mvr", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    fail("glfw", "cannot create a GL 4.5 core window");
  }
  glfwMakeContextCurrent(window);
  gl::loadFunctions([](const char* n) { return reinterpret_cast<void*>(glfwGetProcAddress(n)); });
  auto context = std::make_unique<GlfwContext>(window);
  context->setup();
  return context;
}

}  // namespace mvr
