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

namespace {

GLFWmonitor* panelMonitor = nullptr;
bool panelLost = false;

// The monitor of the given size, if one is connected.
GLFWmonitor* monitorOfSize(int width, int height) {
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  for (int i = 0; i < count; ++i) {
    const GLFWvidmode* mode = glfwGetVideoMode(monitors[i]);
    if (mode && mode->width == width && mode->height == height) return monitors[i];
  }
  return nullptr;
}

}  // namespace

bool GlfwWindow::monitorLost() const { return fullScreen_ && panelLost; }

std::unique_ptr<GlfwWindow> GlfwWindow::open(int width, int height, const std::string& title,
                                             bool visible) {
  return create(width, height, title, visible, false);
}

std::unique_ptr<GlfwWindow> GlfwWindow::openOnPanel(int width, int height, const std::string& title) {
  return create(width, height, title, true, true);
}

std::unique_ptr<GlfwWindow> GlfwWindow::create(int width, int height, const std::string& title, bool visible,
                                               bool onPanel) {
  if (!glfwInit()) fail("glfw", "cannot initialise: no display (set DISPLAY, or run under xvfb-run; rendering alone needs no display with --gl egl)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  GLFWmonitor* monitor = onPanel ? monitorOfSize(width, height) : nullptr;
  if (monitor) {
    panelMonitor = monitor, panelLost = false;
    glfwSetMonitorCallback([](GLFWmonitor* m, int event) {
      if (m == panelMonitor && event == GLFW_DISCONNECTED) panelLost = true;
    });
  }
  GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), monitor, nullptr);
  if (!window) {
    glfwTerminate();
    fail("glfw", "cannot create a GL 4.5 core window");
  }
  glfwMakeContextCurrent(window);
  gl::loadFunctions([](const char* n) { return reinterpret_cast<void*>(glfwGetProcAddress(n)); });
  std::unique_ptr<GlfwWindow> w(new GlfwWindow(window));
  w->fullScreen_ = monitor != nullptr;
  w->finishSetup();
  return w;
}

std::unique_ptr<GlContext> createGlfwContext(int width, int height, bool visible) {
  return GlfwWindow::open(width, height, "mvr", visible);
}

}  // namespace mvr
