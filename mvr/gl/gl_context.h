#pragma once
// A current GL 4.5 core context from one of three platforms. All rendering
// goes to framebuffer objects, so the headless platforms need no surface.
#include <memory>
#include <string>

#include "mvr/names.h"

namespace mvr {

enum class GlPlatform { Auto, Egl, OsMesa, Glfw };
inline constexpr NameTable<GlPlatform, 4> kGlPlatformNames{{{GlPlatform::Auto, "auto"},
                                                            {GlPlatform::Egl, "egl"},
                                                            {GlPlatform::OsMesa, "osmesa"},
                                                            {GlPlatform::Glfw, "glfw"}}};

GlPlatform parseGlPlatform(const std::string& name);  // throws on unknown
const char* glPlatformName(GlPlatform platform);

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  GlPlatform platform() const { return platform_; }
  std::string renderer() const;  // GL_RENDERER
  std::string version() const;   // GL_VERSION
  std::string describe() const;  // "platform: version | renderer"

  // Auto tries EGL (NVIDIA device platform first, then Mesa surfaceless),
  // then OSMesa. GLFW needs a display and is only chosen explicitly.
  static std::unique_ptr<GlContext> create(GlPlatform platform);

 protected:
  explicit GlContext(GlPlatform platform) : platform_(platform) {}
  void finishSetup();  // loads GL functions, checks the version

 private:
  GlPlatform platform_;
};

std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsMesaContext();
// A window of the given size; hidden windows serve as offscreen contexts.
std::unique_ptr<GlContext> createGlfwContext(int width, int height, bool visible);

}  // namespace mvr
