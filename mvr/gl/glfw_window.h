#pragma once
// A GLFW window with a current GL 4.5 core context: the viewer's surface.
// GLFW's own header is left to the files that handle events.
#include <memory>
#include <string>

#include "mvr/gl/gl_context.h"

struct GLFWwindow;

namespace mvr {

class GlfwWindow : public GlContext {
 public:
  // Throws mvr::Error when there is no display.
  static std::unique_ptr<GlfwWindow> open(int width, int height, const std::string& title, bool visible);
  // Full screen on the monitor whose current mode is width x height (a
  // display panel), else a visible window of that size.
  static std::unique_ptr<GlfwWindow> openOnPanel(int width, int height, const std::string& title);
  bool fullScreen() const { return fullScreen_; }
  // The full-screen window's monitor was disconnected.
  bool monitorLost() const;
  ~GlfwWindow() override;
  GLFWwindow* handle() const { return window_; }

 private:
  explicit GlfwWindow(GLFWwindow* window);
  static std::unique_ptr<GlfwWindow> create(int width, int height, const std::string& title, bool visible,
                                            bool onPanel);
  GLFWwindow* window_;
  bool fullScreen_ = false;
};

}  // namespace mvr
