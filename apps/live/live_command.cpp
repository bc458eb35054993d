// mvr live (issue 48). The scene is rendered into a quilt every frame
// (apps/live/live_quilts.h): on the GPU, in the screen's context, straight
// into the texture it shows; on the CPU (llvmpipe), on a render thread of
// its own that hands over a finished quilt once a frame, so that
// rendering frame k + 1 overlaps uploading and showing frame k. It is
// shown through the display's panel
// mapping (mvr/gl/quilt_screen.h): full screen on the monitor of the
// calibration's size, else in a window; without a calibration, the quilt
// itself. A quilt file is shown as it is. Headless (--frames N), the
// frames step 1/30 s of animation each, and a window that cannot open
// gives way to an EGL context and an offscreen screen.
#include "apps/live/live_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include "apps/cli/backend_flags.h"
#include "apps/cli/camera_flags.h"
#include "apps/cli/cli.h"
#include "apps/live/live_quilts.h"
#include "apps/cli/quilt_layout.h"
#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/gl/gl_context.h"
#include "mvr/tone_map.h"
#include "mvr/gl/glfw_window.h"
#include "mvr/gl/quilt_screen.h"
#include "mvr/gl/view_layers.h"
#include "mvr/images/image_file.h"
#include "mvr/images/panel_calibration.h"
#include "mvr/assets/scene_io.h"
#include "mvr/lenticular.h"
#include "mvr/timer.h"

namespace mvr::app {

namespace fs = std::filesystem;

namespace {

const char* const kKeys =
    "drag: orbit; wheel or +/-: zoom; right drag or [ ]: focal plane; arrows: orbit; space: pause; R: reset; "
    "S: screenshot; H: keys; Q or Esc: quit";

// The viewer's hold on the scene: orbit, zoom and focal plane, and the
// clock of its animation and turntable.
struct Controls {
  double yaw = 0.0, pitch = 0.0;  // degrees
  double zoom = 1.0;
  double focal = 0.0;             // world units the scene moved back from the image plane
  bool paused = false, screenshot = false;
  double lastX = -1.0, lastY = -1.0;
  float radius = 1.0f;  // the scene's: the focal plane's steps

  void onKey(GLFWwindow* w, int key) {
    switch (key) {
      case GLFW_KEY_LEFT: yaw -= 5.0; break;
      case GLFW_KEY_RIGHT: yaw += 5.0; break;
      case GLFW_KEY_UP: pitch = std::max(pitch - 5.0, -80.0); break;
      case GLFW_KEY_DOWN: pitch = std::min(pitch + 5.0, 80.0); break;
      case GLFW_KEY_EQUAL:
      case GLFW_KEY_KP_ADD: zoom *= 1.1; break;
      case GLFW_KEY_MINUS:
      case GLFW_KEY_KP_SUBTRACT: zoom /= 1.1; break;
      case GLFW_KEY_LEFT_BRACKET: focal -= 0.05 * radius; break;
      case GLFW_KEY_RIGHT_BRACKET: focal += 0.05 * radius; break;
      case GLFW_KEY_SPACE: paused = !paused; break;
      case GLFW_KEY_R: *this = Controls{.radius = radius}; break;
      case GLFW_KEY_S: screenshot = true; break;
      case GLFW_KEY_H: std::fprintf(stderr, "mvr: keys: %s\n", kKeys); break;
      case GLFW_KEY_Q:
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); break;
      default: break;
    }
  }

  void onCursor(GLFWwindow* w, double x, double y) {
    const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (lastX >= 0.0 && left) {
      yaw += 0.4 * (x - lastX);
      pitch = std::clamp(pitch + 0.4 * (y - lastY), -80.0, 80.0);
    }
    if (lastX >= 0.0 && right) focal += 0.005 * radius * (y - lastY);
    lastX = x, lastY = y;
  }

  // The scene moved as the viewer holds it: turned about its centre
  // (yaw about +y, right-handed like --turntable, then pitch about +x),
  // scaled there, and moved back by the focal offset.
  glm::mat4 move(const glm::vec3& pivot, double turntableDegrees) const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, float(-focal)) + pivot);
    m = glm::scale(m, glm::vec3(float(zoom)));
    m = glm::rotate(m, glm::radians(float(pitch)), glm::vec3(1, 0, 0));
    m = glm::rotate(m, glm::radians(float(yaw + turntableDegrees)), glm::vec3(0, 1, 0));
    return glm::translate(m, -pivot);
  }
};

// Frame intervals, for the readout and the summary line.
class FrameClock {
 public:
  void tick() {
    const double now = since_.seconds();
    intervals_.push_back(now - last_);
    last_ = now;
  }
  int frames() const { return int(intervals_.size()); }
  double seconds() const { return last_; }
  double fps() const { return last_ > 0.0 ? frames() / last_ : 0.0; }
  double quantileMs(double q) const {
    if (intervals_.empty()) return 0.0;
    std::vector<double> v = intervals_;
    const size_t k = std::min(v.size() - 1, size_t(std::ceil(q * double(v.size()))) - (q > 0.0 ? 1 : 0));
    std::nth_element(v.begin(), v.begin() + long(k), v.end());
    return 1e3 * v[k];
  }

 private:
  Stopwatch since_;
  double last_ = 0.0;
  std::vector<double> intervals_;
};

struct LiveFlags {
  std::string source, display = "portrait", calibration, screenshot, clip, path = "auto";
  std::optional<int> frames;
  std::pair<int, int> size{0, 0};  // 0 x 0: the preset's tile
  double turntable = 0.0;  // degrees a second
  LookOptions look;
  std::string tonemap = "none";
  BackendFlags backend;
  CameraFlags camera;

  void add(CLI::App& app) {
    app.add_option("SCENE|QUILT", source,
                   "a scene to render every frame (default: the bundled teacup), or a quilt image to show");
    app.add_option("--display", display,
                   "the display whose quilt is rendered: a preset (go, portrait, 16-landscape, 16-portrait, "
                   "32-landscape, 32-portrait, 65) or COLSxROWS")
        ->capture_default_str();
    addSizeOption(app, "size", size, "each view's size in pixels (default: the display preset's tile)");
    app.add_option("--calibration", calibration,
                   "the display's visual.json: show the panel's native image (full screen on the monitor of its "
                   "size); without it, the quilt")
        ->type_name("FILE");
    app.add_option("--turntable", turntable, "turn the scene about its vertical axis, DEG degrees a second")
        ->type_name("DEG");
    app.add_option("--clip", clip, "play only the scene's animation clip of this name")->type_name("NAME");
    app.add_option("--frames", frames,
                   "headless: show N frames (1/30 s of animation each) as fast as they come, print the rate, exit")
        ->check(CLI::Range(1, 1000000))
        ->type_name("N");
    app.add_option("--screenshot", screenshot, "save the last frame as shown (with --frames; alone, after one)")
        ->type_name("FILE");
    app.add_option("--path", path,
                   "where the views are rendered: gpu (in the screen's GL context, into the texture it shows; the "
                   "GPU spans and the view renderers read nothing back), cpu (on a thread and GL context of their "
                   "own, uploaded once a frame) or auto (default: cpu where GL renders on the CPU, llvmpipe; else "
                   "gpu)")
        ->check(CLI::IsMember({"auto", "gpu", "cpu"}))
        ->type_name("auto|gpu|cpu");
    addLookOptions(app, look);
    addToneMapOption(app, tonemap);
    backend.add(app);
    camera.add(app);
  }
};

bool isQuiltFile(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return fs::is_regular_file(path) && (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".exr" ||
                                       ext == ".tif" || ext == ".tiff");
}

RenderJob liveJob(const LiveFlags& f, QuiltLayout display) {
  if (f.size.first > 0) {
    display.quiltWidth = f.size.first * display.columns;
    display.quiltHeight = f.size.second * display.rows;
  }
  if (display.quiltWidth == 0) fail("--display", "a COLSxROWS grid needs --size (a preset gives its tile size)");
  RenderJob job;
  job.backendFlags = f.backend;
  job.backend = f.backend.resolve();
  job.camera = f.camera;
  job.camera.validate();
  job.scenePath = f.source.empty() ? defaultScenePath() : f.source;
  job.look = f.look;
  job.toneMap = *toneMapNamed(f.tonemap);
  job.quilt = display;
  job.views = display.columns * display.rows;
  job.width = display.tileWidth(), job.height = display.tileHeight();
  job.type = PixelType::Srgb8;
  job.format = "png", job.order = "view";
  job.platform = GlPlatform::Egl;  // the CPU path's render thread's own context, beside the window's
  job.sequence.clip = f.clip;
  return job;
}

// The window (or, headless without a display, an EGL context whose
// screen is offscreen).
struct Surface {
  std::unique_ptr<GlfwWindow> window;
  std::unique_ptr<GlContext> headless;
  bool offscreen() const { return !window; }
};

Surface openSurface(int width, int height, bool headless) {
  Surface s;
  if (!headless) {
    s.window = GlfwWindow::openOnPanel(width, height, "mvr live");
    return s;
  }
  try {
    s.window = GlfwWindow::open(width, height, "mvr live", false);
  } catch (const Error&) {
    s.headless = GlContext::create(GlPlatform::Egl);
  }
  return s;
}

// Where a frame's time went, on stderr: on the CPU path the two threads
// overlap; on the GPU path, a frame's commands, and whether anything came
// back; then the renderer's stages.
void reportFrameTime(const std::string& label, const LiveQuilts* quilts, const ViewLayersSink* layers, int frames,
                     double showSeconds, const std::string& shown) {
  const std::string where = !layers ? "its own thread"
                            : layers->uploads() == 0 ? "the screen's context, into its texture on the GPU, nothing read back"
                                                     : "the screen's context, read back and uploaded";
  std::fprintf(stderr, "mvr: live: %s; a frame: rendering %.1f ms (%s), showing %.1f ms (%s, swap)\n", label.c_str(),
               quilts ? 1e3 * quilts->renderSeconds() / frames : 0.0, where.c_str(), 1e3 * showSeconds / frames,
               shown.c_str());
  if (!quilts) return;
  std::string stages;
  for (const auto& [stage, seconds] : quilts->stages().seconds) {
    char ms[64];
    std::snprintf(ms, sizeof ms, "%s%s %.2f ms", stages.empty() ? "" : ", ", stage.c_str(), 1e3 * seconds / frames);
    stages += ms;
  }
  std::fprintf(stderr, "mvr: live: rendering's stages a frame: %s\n", stages.c_str());
}

}  // namespace

int runLive(int argc, char** argv) {
  CLI::App app("Renders the scene into a quilt every frame and shows it through a lenticular display's mapping "
               "(docs/DISPLAY.md), live: full screen on the display, or in a window.",
               "mvr live");
  app.footer(std::string("Keys: ") + kKeys + ".");
  LiveFlags f;
  f.add(app);
  addThreadsOption(app);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
  const bool headless = f.frames.has_value() || !f.screenshot.empty();
  const int frames = f.frames.value_or(headless ? 1 : 0);  // 0: until closed
  const std::optional<PanelCalibration> panel =
      f.calibration.empty() ? std::nullopt : std::optional(readCalibration(f.calibration));

  // The quilt: a file's, or the renderer's.
  std::optional<Image> still;
  std::optional<RenderJob> job;
  QuiltGrid grid;
  if (isQuiltFile(f.source)) {
    still = readImage(f.source);
    if (!isByteType(still->type)) fail(f.source, "live shows 8-bit quilts");
    const QuiltFile layout = readQuiltLayout(f.source, still->width, still->height);
    grid = {layout.columns, layout.rows, layout.views, still->width / layout.columns, still->height / layout.rows};
  } else {
    const QuiltLayout display = parseQuilt(f.display);
    if (display.columns == 0) fail("--display", "give a display preset or COLSxROWS, not auto");
    job = liveJob(f, display);
    grid = liveGrid(*job);
  }
  const int quiltWidth = grid.columns * grid.tileWidth, quiltHeight = grid.rows * grid.tileHeight;
  // The screen: the panel's, or the quilt scaled to fit 1024 pixels.
  const double fit = std::min(1.0, 1024.0 / std::max(quiltWidth, quiltHeight));
  const int width = panel ? panel->screenW : std::max(1, int(quiltWidth * fit));
  const int height = panel ? panel->screenH : std::max(1, int(quiltHeight * fit));
  Surface surface = openSurface(width, height, headless);
  if (surface.window) glfwSwapInterval(headless ? 0 : 1);
  std::optional<LenticularMap> map;
  if (panel) map = LenticularMap::of(*panel, grid, quiltHeight);
  // The renderer: in the screen's context on a GPU, into its texture,
  // in the renderer's order; else on its thread, into EPI volumes.
  std::unique_ptr<LiveQuilts> quilts;
  std::string label = "quilt";
  ViewLayout layout = ViewLayout::Quilt;
  const bool onScreen = f.path == "gpu" || (f.path == "auto" && !gl::rendersOnCpu());
  if (job) {
    quilts = std::make_unique<LiveQuilts>(std::move(*job), onScreen);
    label = quilts->label();
    layout = onScreen && quilts->order() == FrameOrder::View ? ViewLayout::ViewArray : ViewLayout::EpiVolume;
  }
  QuiltScreen screen(width, height, grid, layout, map, surface.offscreen());
  std::optional<ViewLayersSink> layers;
  if (quilts && onScreen) {
    layers.emplace(screen.viewsTexture(), layout, grid.tileWidth, grid.views, grid.tileHeight);
    quilts->attach(*layers);
  }

  Controls controls;
  GLFWwindow* w = surface.window ? surface.window->handle() : nullptr;
  const float radius = quilts ? quilts->radius() : 1.0f;
  controls.radius = radius;
  if (w && !headless) {
    glfwSetWindowUserPointer(w, &controls);
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
      if (action == GLFW_PRESS || action == GLFW_REPEAT)
        static_cast<Controls*>(glfwGetWindowUserPointer(win))->onKey(win, key);
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
      static_cast<Controls*>(glfwGetWindowUserPointer(win))->zoom *= std::pow(1.1, dy);
    });
  }
  // The scene's clock: real time live (stopped while paused), 1/30 s a frame headless.
  Stopwatch wall;
  double played = 0.0, lastWall = 0.0;
  auto poseOf = [&](int k) {
    const double now = wall.seconds();
    if (!controls.paused) played += now - lastWall;
    lastWall = now;
    const double t = headless ? k / 30.0 : played;
    const double length = quilts->animationLength();
    LivePose pose;
    pose.time = length > 0.0 ? std::fmod(t, length) : t;
    controls.focal = std::clamp(controls.focal, -10.0 * radius, 10.0 * radius);
    pose.move = controls.move(quilts->pivot(), f.turntable * t);
    return pose;
  };
  if (quilts) quilts->request(poseOf(0));
  if (still) screen.upload(*still);
  FrameClock clock;
  double lastTitle = 0.0, showSeconds = 0.0;
  for (int k = 0; frames == 0 || k < frames; ++k) {
    if (w) {
      glfwPollEvents();
      if (glfwWindowShouldClose(w)) break;
      if (surface.window->monitorLost()) {
        std::fprintf(stderr, "mvr: live: the display went away\n");
        break;
      }
      if (!headless) {
        double x = 0, y = 0;
        glfwGetCursorPos(w, &x, &y);
        controls.onCursor(w, x, y);
      }
    }
    const Image* quilt = quilts ? quilts->take() : nullptr;  // frame k (on the GPU path, drawn into the screen)
    const Stopwatch show;
    if (quilts && (frames == 0 || k + 1 < frames)) quilts->request(poseOf(k + 1));
    if (quilt) screen.upload(*quilt);
    screen.draw();
    if (w && !surface.offscreen()) glfwSwapBuffers(w);
    screen.finish();
    showSeconds += show.seconds();
    clock.tick();
    if (controls.screenshot) {
      char name[64];
      std::snprintf(name, sizeof name, "mvr_live_%04d.png", k);
      writeImage(screen.read(), name);
      std::fprintf(stderr, "mvr: saved %s\n", name);
      controls.screenshot = false;
    }
    if (w && clock.seconds() - lastTitle > 0.5) {
      char title[128];
      std::snprintf(title, sizeof title, "mvr live: %.1f fps (%s, %d views)", clock.fps(), label.c_str(), grid.views);
      glfwSetWindowTitle(w, title);
      lastTitle = clock.seconds();
    }
  }
  if (!f.screenshot.empty()) writeImage(screen.read(), f.screenshot);
  std::printf("mvr: live: %d frames, %.1f fps (median %.1f ms, p99 %.1f ms)\n", clock.frames(), clock.fps(),
              clock.quantileMs(0.5), clock.quantileMs(0.99));
  const std::string shown = std::string(layers ? "" : "upload, ") + (panel ? "panel mapping" : "quilt scaled");
  reportFrameTime(label, quilts.get(), layers ? &*layers : nullptr, std::max(clock.frames(), 1), showSeconds, shown);
  return 0;
}

}  // namespace mvr::app
