#include "apps/native/native_command.h"

#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli/cli.h"
#include "apps/cli/quilt_layout.h"
#include "mvr/error.h"
#include "mvr/gl/gl_context.h"
#include "mvr/gl/lenticular_pass.h"
#include "mvr/images/image_file.h"
#include "mvr/images/panel_calibration.h"
#include "mvr/lenticular.h"
#include "mvr/timer.h"

namespace mvr::app {

int runNative(int argc, char** argv) {
  CLI::App app("Maps a quilt to a lenticular display's native image: each subpixel of the panel taken from the "
               "view its lens sends that way (docs/DISPLAY.md), by the display's calibration (Looking Glass's "
               "visual.json).",
               "mvr native");
  std::string quiltPath, calibrationPath, out, mapping = "gl", platform = "auto";
  app.add_option("QUILT", quiltPath, "an 8-bit quilt whose layout its name (_qs{C}x{R}a{aspect}) or EXIF states")
      ->required();
  app.add_option("--calibration", calibrationPath, "the display's visual.json")->required();
  app.add_option("--out", out, "the native image, screenW x screenH (.png)")->required();
  app.add_option("--mapping", mapping, "where the mapping runs: one GL pass (gl), or its CPU twin (cpu)")
      ->check(CLI::IsMember({"gl", "cpu"}))
      ->capture_default_str();
  app.add_option("--gl", platform, "GL platform for --mapping gl")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
      ->capture_default_str();
  addThreadsOption(app);
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;
  const Stopwatch watch;
  const PanelCalibration panel = readCalibration(calibrationPath);
  const Image quilt = readImage(quiltPath);
  if (!isByteType(quilt.type)) fail(quiltPath, "the native image is made from an 8-bit quilt");
  const QuiltFile layout = readQuiltLayout(quiltPath, quilt.width, quilt.height);
  const QuiltGrid grid{layout.columns, layout.rows, layout.views, quilt.width / layout.columns,
                       quilt.height / layout.rows};
  const LenticularMap map = LenticularMap::of(panel, grid, quilt.height);
  Image native;
  if (mapping == "gl") {
    const std::unique_ptr<GlContext> context = GlContext::create(parseGlPlatform(platform));
    native = LenticularPass(map).render(quilt);
  } else {
    native = nativeImage(quilt, map);
  }
  writeImage(native, out);
  std::fprintf(stderr, "mvr: native: %d views of %dx%d to %dx%d (%s) in %s in %.3f s\n", layout.views,
               grid.tileWidth, grid.tileHeight, native.width, native.height, mapping.c_str(), out.c_str(),
               watch.seconds());
  return 0;
}

}  // namespace mvr::app
