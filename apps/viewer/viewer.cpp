#include "apps/viewer/viewer.h"

#include "mvr/gl/gl_api.h"  // before GLFW

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "apps/cli/backend_flags.h"
#include "apps/cli/camera_flags.h"
#include "apps/cli/cli.h"
#include "apps/cli/quilt_layout.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/frames/volume.h"
#include "mvr/error.h"
#include "mvr/gl/view_panel.h"
#include "mvr/gl/glfw_window.h"
#include "mvr/images/image_file.h"
#include "mvr/images/manifest.h"
#include "mvr/assets/scene_io.h"

namespace mvr::app {

namespace {

namespace fs = std::filesystem;

// A view set in memory: views[row][view], all the same size.
struct ViewSet {
  int views = 0, rows = 1, width = 0, height = 0;
  std::vector<std::vector<Image>> images;
};

// The views of a quilt of `columns` x `tileRows` tiles: a single row from
// view 0 at the bottom left, left to right, then upwards; a grid's rows of
// views as rows of tiles, row 0 at the top (docs/CONVENTIONS.md).
ViewSet quiltViews(const Image& quilt, int columns, int tileRows, int views, int rows) {
  ViewSet set;
  set.views = views;
  set.rows = rows;
  set.width = quilt.width / columns;
  set.height = quilt.height / tileRows;
  set.images.resize(rows);
  for (int r = 0; r < rows; ++r)
    for (int v = 0; v < views; ++v) {
      const int x0 = (rows > 1 ? v : v % columns) * set.width;
      const int y0 = (rows > 1 ? r : tileRows - 1 - v / columns) * set.height;
      Image tile(set.width, set.height, quilt.type);
      for (int y = 0; y < set.height; ++y)
        std::memcpy(tile.row(y), quilt.row(y0 + y) + size_t(x0) * 4 * Image::channelBytes(quilt.type),
                    tile.rowBytes());
      set.images[r].push_back(std::move(tile));
    }
  return set;
}

// A set written with --quilt-only: its views are the quilt's tiles, laid
// out as its manifest says.
ViewSet loadQuiltOfSet(const std::string& dir, const Manifest& manifest) {
  const nlohmann::json& layout = manifest.info.value("quilt_layout", nlohmann::json::object());
  if (!manifest.info.contains("quilt") || !layout.contains("columns") || !layout.contains("rows"))
    fail(dir, "holds neither view images nor a quilt the manifest describes");
  const std::string path = (fs::path(dir) / manifest.info["quilt"].get<std::string>()).string();
  const Image quilt = readImage(path);
  const int columns = layout["columns"], tileRows = layout["rows"];
  if (columns < 1 || tileRows < 1 || quilt.width != columns * manifest.width ||
      quilt.height != tileRows * manifest.height || long(columns) * tileRows < long(manifest.views) * manifest.rows)
    fail(path, "is not the " + std::to_string(columns) + "x" + std::to_string(tileRows) + " quilt of " +
                   std::to_string(manifest.width) + "x" + std::to_string(manifest.height) +
                   " views the manifest describes");
  return quiltViews(quilt, columns, tileRows, manifest.views, manifest.rows);
}

ViewSet loadSet(const std::string& dir) {
  const Manifest manifest = Manifest::read(dir);
  if (manifest.order != "view") fail(dir, "holds EPIs; render with --order view to view it");
  if (!fs::exists(fs::path(dir) / manifest.viewName(0, 0))) return loadQuiltOfSet(dir, manifest);
  ViewSet set;
  set.views = manifest.views;
  set.rows = manifest.rows;
  set.images.resize(set.rows);
  for (int r = 0; r < set.rows; ++r)
    for (int v = 0; v < set.views; ++v) {
      Image img = readImage((fs::path(dir) / manifest.viewName(r, v)).string());
      if (set.width == 0) set.width = img.width, set.height = img.height;
      if (img.width != set.width || img.height != set.height) fail(dir, "views differ in size");
      set.images[r].push_back(std::move(img));
    }
  return set;
}

// A quilt's tiles as a set of one row: view 0 at the bottom left, left to
// right, then upwards (docs/CONVENTIONS.md).
ViewSet loadQuilt(const std::string& path) {
  const Image quilt = readImage(path);
  const QuiltFile layout = readQuiltLayout(path, quilt.width, quilt.height);
  return quiltViews(quilt, layout.columns, layout.rows, layout.views, 1);
}

// The middle of the rows where a view shows anything: the scanline whose
// EPI crosses the object. The image's middle when it is empty.
int objectMiddleRow(const Image& view) {
  int first = -1, last = -1;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x)
      if (view.pixel(x, y).a > 0.0f) {
        if (first < 0) first = y;
        last = y;
        break;
      }
  return first < 0 ? view.height / 2 : (first + last) / 2;
}

// Collects rendered views in memory, converted to 8 bits for display.
class ViewCollector final : public FrameSink {
 public:
  explicit ViewCollector(ViewSet& set) : set_(set) {}
  void putView(int row, int view, const Image& image) override { set_.images[row][view] = image; }

 private:
  ViewSet& set_;
};

const char* const kKeys =
    "left/right view, up/down row, mouse over the view picks the scanline, drag scrubs views, "
    "S saves mvr_screenshot_NNNN.png, H lists keys, Q or Esc quits";

class Viewer {
 public:
  // The EPI panel takes at most 512 window rows.
  Viewer(ViewSet set, GlfwWindow& window, int view, int scanline, bool overlay)
      : set_(std::move(set)), window_(window), view_(view), scanline_(scanline), overlay_(overlay),
        panel_(set_.width, set_.height, set_.views, std::min(set_.views, 512)) {
    clampState();
    upload();
  }

  int windowRows() const { return panel_.windowRows(); }

  void draw() { panel_.draw(overlay_ ? glm::ivec2(view_, scanline_) : glm::ivec2(-1)); }

  // The window as an image, rows top first.
  Image screenshot() const { return panel_.read(); }

  void run() {
    GLFWwindow* w = window_.handle();
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
      if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
      static_cast<Viewer*>(glfwGetWindowUserPointer(win))->onKey(key);
    });
    glfwShowWindow(w);
    int shots = 0;
    double lastX = 0, lastY = 0;
    glfwGetCursorPos(w, &lastX, &lastY);  // where it rests at start does not pick a scanline
    while (!glfwWindowShouldClose(w)) {
      double cx = 0, cy = 0;
      glfwGetCursorPos(w, &cx, &cy);
      const bool dragging = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
      if (cx != lastX || cy != lastY || dragging) onCursor(cx, cy, dragging);
      lastX = cx, lastY = cy;
      draw();
      if (saveRequested_) {
        char name[64];
        std::snprintf(name, sizeof name, "mvr_screenshot_%04d.png", shots++);
        writeImage(screenshot(), name);
        std::fprintf(stderr, "mvr: saved %s\n", name);
        saveRequested_ = false;
      }
      glfwSwapBuffers(w);
      glfwWaitEventsTimeout(0.05);
    }
  }

 private:
  void onKey(int key) {
    switch (key) {
      case GLFW_KEY_LEFT: --view_; break;
      case GLFW_KEY_RIGHT: ++view_; break;
      case GLFW_KEY_UP: --row_; break;
      case GLFW_KEY_DOWN: ++row_; break;
      case GLFW_KEY_S: saveRequested_ = true; return;
      case GLFW_KEY_H:
        std::fprintf(stderr, "mvr: keys: %s\n", kKeys);
        glfwSetWindowTitle(window_.handle(), kKeys);
        return;
      case GLFW_KEY_Q:
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window_.handle(), GLFW_TRUE); return;
      default: return;
    }
    clampState();
    upload();
  }

  void onCursor(double x, double y, bool dragging) {
    bool changed = false;
    if (y >= 0 && y < set_.height && int(y) != scanline_) {
      scanline_ = int(y);
      changed = true;
    }
    if (dragging && lastX_ >= 0 && std::abs(x - lastX_) >= 2) {
      view_ += x > lastX_ ? 1 : -1;
      changed = true;
    }
    lastX_ = dragging ? x : -1;
    if (changed) {
      clampState();
      upload();
    }
  }

  void clampState() {
    view_ = std::clamp(view_, 0, set_.views - 1);
    row_ = std::clamp(row_, 0, set_.rows - 1);
    scanline_ = std::clamp(scanline_, 0, set_.height - 1);
    char title[96];
    std::snprintf(title, sizeof title, "mvr view: row %d view %d scanline %d", row_, view_, scanline_);
    glfwSetWindowTitle(window_.handle(), title);
  }

  void upload() {
    Image epi(set_.width, set_.views, PixelType::U8);
    for (int i = 0; i < set_.views; ++i)
      std::memcpy(epi.row(i), set_.images[row_][i].row(scanline_), epi.rowBytes());
    panel_.upload(set_.images[row_][view_], epi);
  }

  ViewSet set_;
  GlfwWindow& window_;
  int view_, row_ = 0, scanline_;
  bool overlay_, saveRequested_ = false;
  double lastX_ = -1;
  gl::ViewPanel panel_;
};

// 8-bit copies for display: float sets (linear) are clamped and
// sRGB-encoded; 8-bit files are shown as they store their values.
void toDisplay(ViewSet& set) {
  for (auto& row : set.images)
    for (Image& img : row) {
      if (isByteType(img.type)) continue;
      Image out(img.width, img.height, PixelType::Srgb8);
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) out.setLinear(x, y, img.linear(x, y));
      img = std::move(out);
    }
}

// A start outside the set is an error, not a silent clamp.
void checkStart(const ViewSet& set, const std::optional<int>& view, const std::optional<int>& scanline) {
  if (view && *view >= set.views)
    fail("--view", std::to_string(*view) + " is beyond the set's views 0.." + std::to_string(set.views - 1));
  if (scanline && *scanline >= set.height)
    fail("--scanline", std::to_string(*scanline) + " is beyond the set's scanlines 0.." + std::to_string(set.height - 1));
}

}  // namespace

int runView(int argc, char** argv) {
  CLI::App app("Shows one view of a rendered set (a folder with manifest.json) with the EPI of "
               "one scanline below it. Given a scene instead, renders it first (--views, "
               "--size, --backend and its options, and the camera options, as for render).",
               "mvr view");
  app.footer(std::string("Keys: ") + kKeys + ".");
  std::string source, screenshot;
  int views = 32, rows = 1;
  std::optional<int> startView, startScanline;
  std::pair<int, int> size{320, 240};
  BackendFlags backend;
  app.add_option("DIR|QUILT|SCENE", source,
                 "a rendered set, a quilt image (..._qs{C}x{R}a{aspect}.png) or a scene to render")
      ->required();
  app.add_option("--view", startView, "start at this view (default: the middle one)")->check(CLI::NonNegativeNumber);
  app.add_option("--scanline", startScanline, "start at this scanline (default: the middle of the object)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--screenshot", screenshot, "draw one frame, save it, exit (for tests, under Xvfb)")
      ->type_name("FILE");
  addViewCountOptions(app, views, rows);
  addSizeOption(app, "size", size, "scene: image size in pixels");
  backend.add(app);
  CameraFlags camera;
  camera.add(app);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;

  const bool shot = !screenshot.empty();
  ViewSet set;
  std::unique_ptr<GlfwWindow> window;
  const bool quilt = fs::is_regular_file(source) && fs::path(source).filename().string().find("_qs") != std::string::npos;
  if (fs::is_directory(source) || quilt) {
    if (const std::string flag = camera.firstGiven(); !flag.empty())
      fail(flag, "applies to a scene (a rendered set or quilt has its camera)");
    set = quilt ? loadQuilt(source) : loadSet(source);
    checkStart(set, startView, startScanline);
    window = GlfwWindow::open(set.width, set.height + std::min(set.views, 512), "mvr view", false);
  } else {  // live: render the scene in this window's context
    BackendOptions options = backend.resolve();
    camera.validate();
    Scene scene = loadInputScene(source, false);
    const auto [w, h] = size;
    // The camera as render frames it: the file's camera, the focal plane,
    // then the display-terms adjustments.
    camera.viewThroughFileCamera(scene, w, h);
    camera.placeFocalPlane(scene);
    set.views = views;
    set.rows = rows;
    set.width = w;
    set.height = h;
    set.images.assign(set.rows, std::vector<Image>(set.views));
    checkStart(set, startView, startScanline);
    window = GlfwWindow::open(w, h + std::min(set.views, 512), "mvr view", false);
    ShearingCamera cam(camera.adjust(cameraFor(scene, w, h), w, h), w, h, set.views, set.rows);
    backend.chooseDefaultPst(options, scene);
    auto renderer = makeRenderer(options, scene, PixelType::Srgb8);
    ViewCollector collect(set);
    std::optional<BackgroundSink> background;
    if (const auto color = camera.backgroundColor()) background.emplace(collect, *color);
    FrameSink& views = background ? static_cast<FrameSink&>(*background) : collect;
    std::unique_ptr<EpisToViews> reorder;
    if (renderer->order() == FrameOrder::Epi)
      reorder = std::make_unique<EpisToViews>(views, w, h, set.views, PixelType::Srgb8);
    RenderStats stats;
    renderer->render(cam, reorder ? static_cast<FrameSink&>(*reorder) : views, stats);
  }
  toDisplay(set);
  const int view = startView.value_or(set.views / 2);
  const int scanline = startScanline.value_or(objectMiddleRow(set.images[0][view]));
  Viewer viewer(std::move(set), *window, view, scanline, !shot);
  if (shot) {
    viewer.draw();
    writeImage(viewer.screenshot(), screenshot);
    return 0;
  }
  viewer.run();
  return 0;
}

}  // namespace mvr::app
