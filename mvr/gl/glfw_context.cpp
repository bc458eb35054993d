// GLFW windows: the interactive viewer's context, or a hidden window.
#include "mvr/gl/gl_api.h"  // before GLFW: glcorearb.h must come first

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "mvr/error.h"
#include "mvr/gl/glfw_window.h"

namespace mvr {

GlfwWindow::GlfwWindow(GLFWwindow* window) : GlContext(GlPlatform::Glfw), window_(window) {}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::unique_ptr<GlfwWindow> GlfwWindow::open(int width, int height, const std::string& title,
                                             bool visible) {
  if (!glfwInit()) fail("glfw", "cannot initialise: no display (set DISPLAY, or run under xvfb-run; rendering alone needs no display with --gl egl)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    fail("glfw", "cannot create a GL 4.5 core window");
  }
  glfwMakeContextCurrent(window);
  gl::loadFunctions([](const char* n) { return reinterpret_cast<void*>(glfwGetProcAddress(n)); });
  std::unique_ptr<GlfwWindow> w(new GlfwWindow(window));
  w->finishSetup();
  return w;
}

std::unique_ptr<GlContext> createGlfwContext(int width, int height, bool visible) {
  return GlfwWindow::open(width, height, "mvr", visible);
}

}  // namespace mvr
