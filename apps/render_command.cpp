#include "apps/render_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>

#include "apps/args.h"
#include "epi/epi_stream.h"
#include "epi/mvr_renderer.h"
#include "epi/volume.h"
#include "mvr/baselines.h"
#include "mvr/error.h"
#include "mvr/gl_context.h"
#include "mvr/image_set.h"
#include "mvr/scene_io.h"

namespace mvr::app {

const char* const kRenderHelp =
    "usage: mvr render [SCENE] [options]\n"
    "SCENE is a JSON scene file or a mesh (OBJ, PLY, OFF, STL); without it the\n"
    "bundled default scene is rendered.\n"
    "  --backend mvr|svr|svr-layered|deferred   renderer (default mvr)\n"
    "  --pst quad|strip|exact|cpu   MVR accuracy mode (default strip)\n"
    "  --views N          views on the horizontal track (default 16)\n"
    "  --rows M           rows of views for full parallax (default 1)\n"
    "  --size WxH         image size in pixels (default 320x240)\n"
    "  --out DIR          output folder (default out)\n"
    "  --format png|exr|tiff   image format (default png; exr renders in float)\n"
    "  --order view|epi   write views (view_*) or EPIs (epi_*) (default view)\n"
    "  --stream PATH|-    write the raw EPI-major stream (docs/EPI_STREAM.md) to a\n"
    "                     file or stdout instead of an image set\n"
    "  --gl egl|osmesa|glfw    GL platform (default: egl, else osmesa)\n"
    "Writes view_0000.png ... (view_r000_c0000.png for grids) and manifest.json.\n";

std::unique_ptr<Renderer> makeRenderer(const BackendChoice& c, const Scene& scene, PixelType type) {
  if (c.backend == "mvr") return makeMvrRenderer(scene, parsePstMode(c.pst), type);
  if (c.backend == "svr") return makeSvrRenderer(scene, type);
  if (c.backend == "svr-layered") return makeLayeredSvrRenderer(scene, type);
  if (c.backend == "deferred") return makeDeferredRenderer(scene, type);
  fail("--backend", "unknown back end '" + c.backend + "' (expected mvr, svr, svr-layered or deferred)");
}

namespace {

nlohmann::json cameraJson(const ShearingCamera& cam) {
  const CameraSpec& s = cam.spec();
  return {{"distance", s.distance},
          {"image_plane", {cam.planeWidth(), cam.planeHeight()}},
          {"track", {s.trackLeft, s.trackRight}},
          {"rows_track", {s.rowTop, s.rowBottom}},
          {"near", s.nearDistance},
          {"far", s.farDistance},
          {"view_spacing", cam.viewSpacing()}};
}

// EPIs straight to a file or stdout as they complete. A file is written
// under a temporary name and renamed when complete.
int runStream(Renderer& renderer, const ShearingCamera& cam, const std::string& path,
              PixelType type) {
  namespace fs = std::filesystem;
  EpiStreamHeader header{uint32_t(cam.width()), uint32_t(cam.height()), uint32_t(cam.views()),
                         uint32_t(cam.rows()), 4, uint32_t(Image::channelBytes(type))};
  std::ofstream file;
  const std::string part = path + ".part";
  if (path != "-") {
    file.open(part, std::ios::binary);
    if (!file) fail(path, "cannot open stream file");
  }
  std::ostream& out = path == "-" ? std::cout : file;
  try {
    EpiStreamWriter stream(out, header);
    std::unique_ptr<FrameSink> adaptor;
    if (renderer.order() == FrameOrder::View)
      adaptor = std::make_unique<ViewsToEpis>(stream, cam.width(), cam.height(), cam.views(), type);
    FrameSink& sink = adaptor ? *adaptor : stream;
    RenderStats stats;
    renderer.render(cam, sink, stats);
    sink.finish();
  } catch (...) {
    std::error_code ec;
    if (path != "-") fs::remove(part, ec);
    throw;
  }
  if (path != "-") {
    file.close();
    std::error_code ec;
    fs::rename(part, path, ec);
    if (ec) fail(path, "cannot finish stream file: " + ec.message());
  }
  return 0;
}

}  // namespace

int runRender(int argc, char** argv) {
  Args args(argc, argv, 2,
            {"backend", "pst", "views", "rows", "size", "out", "format", "order", "gl", "stream"}, {});
  if (args.positional().size() > 1) fail("render", "takes at most one scene file");
  const std::string scenePath =
      args.positional().empty() ? defaultScenePath() : args.positional()[0];
  BackendChoice choice{args.get("backend", "mvr"), args.get("pst", "strip")};
  const int views = args.getInt("views", 16, 1, 65536);
  const int rows = args.getInt("rows", 1, 1, 4096);
  const auto [width, height] = args.getSize("size", {320, 240});
  const std::string out = args.get("out", "out");
  const std::string format = args.get("format", "png");
  const PixelType type = format == "png" ? PixelType::U8 : PixelType::F32;
  const std::string order = args.get("order", "view");
  if (order != "view" && order != "epi") fail("--order", "expected view or epi, not '" + order + "'");
  if (choice.backend != "mvr" && args.has("pst")) fail("--pst", "applies to --backend mvr only");
  const GlPlatform platform = parseGlPlatform(args.get("gl", "auto"));

  // Input problems first, before any GL or file work.
  Scene scene = loadScene(scenePath);
  ShearingCamera camera(cameraFor(scene, width, height), width, height, views, rows);
  auto context = GlContext::create(platform);
  auto renderer = makeRenderer(choice, scene, type);

  if (args.has("stream"))
    return runStream(*renderer, camera, args.get("stream", "-"), type);

  ImageSetWriter writer(out, format, views, rows, height);
  // Reorder only when the renderer's natural order is not the one asked for.
  std::unique_ptr<FrameSink> adaptor;
  if (renderer->order() == FrameOrder::Epi && order == "view")
    adaptor = std::make_unique<EpisToViews>(writer, width, height, views, type);
  else if (renderer->order() == FrameOrder::View && order == "epi")
    adaptor = std::make_unique<ViewsToEpis>(writer, width, height, views, type);
  FrameSink& sink = adaptor ? *adaptor : writer;
  RenderStats stats;
  Stopwatch total;
  renderer->render(camera, sink, stats);
  sink.finish();

  nlohmann::json m;
  m["scene"] = scene.source;
  m["triangles"] = scene.triangleCount();
  m["backend"] = renderer->name();
  if (choice.backend == "mvr") m["pst"] = choice.pst;
  m["views"] = views;
  m["rows"] = rows;
  m["width"] = width;
  m["height"] = height;
  m["format"] = format;
  m["order"] = order;
  if (order == "view") m["naming"] = rows == 1 ? "view_%04d" : "view_r%03d_c%04d";
  else m["naming"] = rows == 1 ? "epi_%04d (rows: views)" : "epi_r%03d_%04d (rows: views)";
  m["gl"] = {{"platform", glPlatformName(context->platform())},
             {"version", context->version()},
             {"renderer", context->renderer()}};
  m["camera"] = cameraJson(camera);
  m["timings_s"] = stats.times.seconds;
  m["timings_s"]["total"] = total.seconds();
  m["counters"] = stats.counters;
  m["notes"] = stats.notes;
  m["files"] = writer.filesWritten();
  writer.commit(m);
  std::fprintf(stderr, "mvr: %s rendered %d view(s) of %dx%d to %s in %.3f s\n",
               renderer->name().c_str(), views * rows, width, height, out.c_str(),
               total.seconds());
  return 0;
}

}  // namespace mvr::app
