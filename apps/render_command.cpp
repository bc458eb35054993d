#include "apps/render_command.h"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include <nlohmann/json.hpp>

#include "apps/args.h"
#include "epi/epi_stream.h"
#include "epi/interp_renderer.h"
#include "epi/mvr_renderer.h"
#include "epi/stream_queue.h"
#include "epi/volume.h"
#include "mvr/baselines/baselines.h"
#include "mvr/error.h"
#include "mvr/frame_sinks.h"
#include "mvr/gl/gl_context.h"
#include "mvr/io/fd_stream.h"
#include "mvr/io/image_set.h"
#include "mvr/io/scene_io.h"

namespace mvr::app {

const char* const kRenderHelp =
    "usage: mvr render [SCENE] [options]\n"
    "SCENE is a JSON scene file or a mesh (OBJ, PLY, OFF, STL); without it the\n"
    "bundled default scene is rendered.\n"
    "  --backend mvr|interp|svr|svr-layered|deferred   renderer (default mvr)\n"
    "  --pst quad|strip|exact|cpu   MVR accuracy mode (default strip; interp: quad)\n"
    "  --acquire center|dual|hierarchical   interp: source views from the middle of\n"
    "                     the track, from both ends (default), or from both ends\n"
    "                     and then halfway between two sources wherever they leave\n"
    "                     holes, recursively\n"
    "  --budget B         interp hierarchical: source views per row at most (default 9)\n"
    "  --splits K         interp: highlights per view, split at K views across each\n"
    "                     specular pixel's highlight (default 0: as the source saw it)\n"
    "  --overlap P        interp: widen each slice by P pixels per side against cracks\n"
    "                     (default 0.25; more closes more holes, dilates outlines)\n"
    "  --visibility       interp: drop layer pixels the nearest layer hides from the\n"
    "                     whole track; stop peeling at a layer with none left\n"
    "  --max-layers L     interp: depth-peeled layers per source view (default 4)\n"
    "  --coalesce T       interp: draw runs of source pixels with close depths as one\n"
    "                     slice when that moves no pixel more than T pixels in any\n"
    "                     view (default 0: a slice per pixel)\n"
    "  --texture vector|direct   MVR texturing: 1-D texture vectors per slice\n"
    "                     (default) or the 2D texture with a per-pixel divide\n"
    "  --views N          views on the horizontal track (default 16)\n"
    "  --rows M           rows of views for full parallax (default 1)\n"
    "  --size WxH         image size in pixels (default 320x240)\n"
    "  --out DIR          output folder (default out)\n"
    "  --format png|exr|tiff   image format (default png; exr renders in float)\n"
    "  --order view|epi   write views (view_*) or EPIs (epi_*) (default view)\n"
    "  --bits 8|16        bits per channel for png and tiff (16 renders in float)\n"
    "  --quilt auto|CxR   also write all views tiled in one quilt image,\n"
    "                     quilt_qs{C}x{R}a{aspect}.{format} (auto: near square)\n"
    "  --predistort LUT   resample every row through a table of source x per column\n"
    "  --stream PATH|-    write the raw EPI-major stream (docs/EPI_STREAM.md) to a\n"
    "                     file or stdout instead of an image set (see mvr stream)\n"
    "  --gl egl|osmesa|glfw    GL platform (default: egl, else osmesa)\n"
    "Writes view_0000.png ... (view_r000_c0000.png for grids) and manifest.json.\n";

std::unique_ptr<Renderer> makeRenderer(const BackendChoice& c, const Scene& scene, PixelType type) {
  if (c.backend == "mvr")
    return makeMvrRenderer(scene, parsePstMode(c.pst), type, 2, parseTextureMode(c.texture));
  if (c.backend == "interp")
    return makeInterpRenderer(scene, type,
                              {.acquire = parseAcquire(c.acquire), .maxLayers = c.maxLayers,
                               .mode = parsePstMode(c.pst), .overlap = c.overlap, .coalesce = c.coalesce,
                               .visibility = c.visibility, .budget = c.budget, .splits = c.splits});
  if (c.backend == "svr") return makeSvrRenderer(scene, type);
  if (c.backend == "svr-layered") return makeLayeredSvrRenderer(scene, type);
  if (c.backend == "deferred") return makeDeferredRenderer(scene, type);
  fail("--backend",
       "unknown back end '" + c.backend + "' (expected mvr, interp, svr, svr-layered or deferred)");
}

namespace {

bool isPlainFile(const std::string& endpoint) {
  return endpoint != "-" && endpoint.rfind("unix:", 0) != 0 && endpoint.rfind("tcp:", 0) != 0;
}

// EPIs to a file, stdout or socket as they complete, through a bounded
// queue. A file is written under a temporary name and renamed when done.
int streamTo(Renderer& renderer, const ShearingCamera& cam, const std::string& endpoint,
             PixelType type, int queue) {
  namespace fs = std::filesystem;
  std::signal(SIGPIPE, SIG_IGN);  // a vanished consumer is an error, not a kill
  const bool file = isPlainFile(endpoint);
  const std::string target = file ? endpoint + ".part" : endpoint;
  EpiStreamHeader header{uint32_t(cam.width()), uint32_t(cam.height()), uint32_t(cam.views()),
                         uint32_t(cam.rows()), 4, uint32_t(Image::channelBytes(type))};
  Stopwatch watch;
  size_t highWater = 0;
  try {
    FdStreamBuf buffer(openForWriting(target));
    std::ostream out(&buffer);
    QueuedEpiStream stream(out, header, size_t(queue));
    std::unique_ptr<FrameSink> adaptor;
    if (renderer.order() == FrameOrder::View)
      adaptor = std::make_unique<ViewsToEpis>(stream, cam.width(), cam.height(), cam.views(), type);
    FrameSink& sink = adaptor ? *adaptor : stream;
    RenderStats stats;
    renderer.render(cam, sink, stats);
    sink.finish();
    highWater = stream.highWater();
  } catch (...) {
    std::error_code ec;
    if (file) fs::remove(target, ec);
    throw;
  }
  if (file) {
    std::error_code ec;
    fs::rename(target, endpoint, ec);
    if (ec) fail(endpoint, "cannot finish stream file: " + ec.message());
  }
  std::fprintf(stderr, "mvr: streamed %d EPIs of %dx%d to %s in %.3f s (queue high water %zu of %d)\n",
               cam.height() * cam.rows(), cam.width(), cam.views(), endpoint.c_str(), watch.seconds(),
               highWater, queue);
  return 0;
}

}  // namespace

const char* const kStreamHelp =
    "usage: mvr stream [SCENE] --to -|FILE|unix:PATH|tcp:HOST:PORT [options]\n"
    "Renders like mvr render and sends each EPI as it completes in the raw\n"
    "EPI-major stream (docs/EPI_STREAM.md). Sockets connect to a listening\n"
    "consumer (mvr-consume). A bounded queue decouples rendering from sending;\n"
    "when the consumer is slow the renderer waits (backpressure).\n"
    "  --queue K          EPIs held at most (default 8)\n"
    "  --backend, --pst, --views, --rows, --size, --format, --gl as for render\n";

int runRender(int argc, char** argv, bool streamCommand) {
  // The render options both commands share; then each command's own.
  std::set<std::string> flags = {"backend", "pst", "texture", "acquire", "max-layers", "coalesce",
                                 "budget", "splits", "overlap", "views", "rows", "size", "format",
                                 "gl", "queue"};
  const auto own = streamCommand ? std::set<std::string>{"to"}
                                 : std::set<std::string>{"out", "order", "stream", "bits", "quilt", "predistort"};
  flags.insert(own.begin(), own.end());
  Args args(argc, argv, 2, flags, {"visibility"});
  const char* streamFlag = streamCommand ? "to" : "stream";
  const bool streaming = args.has(streamFlag);
  if (streamCommand && !streaming) fail("stream", "needs --to -|FILE|unix:PATH|tcp:HOST:PORT");
  if (args.positional().size() > 1) fail("render", "takes at most one scene file");
  const std::string scenePath =
      args.positional().empty() ? defaultScenePath() : args.positional()[0];
  const std::string backend = args.get("backend", "mvr");
  BackendChoice choice{backend, args.get("pst", defaultPst(backend)),
                       args.get("texture", "vector"), args.get("acquire", "dual"),
                       args.getInt("max-layers", 4, 1, 64), float(args.getDouble("coalesce", 0.0)),
                       args.has("visibility"), args.getInt("budget", 9, 2, 1024),
                       args.getInt("splits", 0, 0, 64), float(args.getDouble("overlap", 0.25))};
  const int views = args.getInt("views", 16, 1, 65536);
  const int rows = args.getInt("rows", 1, 1, 4096);
  const auto [width, height] = args.getSize("size", {320, 240});
  const std::string out = args.get("out", "out");
  const std::string format = args.get("format", "png");
  const int bits = args.getInt("bits", 8, 8, 16);
  // 8-bit PNG renders into 8-bit targets; everything else renders in float.
  const PixelType type = format == "png" && bits == 8 ? PixelType::U8 : PixelType::F32;
  const std::string order = args.get("order", "view");
  if (order != "view" && order != "epi") fail("--order", "expected view or epi, not '" + order + "'");
  if (choice.backend != "mvr" && choice.backend != "interp" && args.has("pst"))
    fail("--pst", "applies to --backend mvr and interp only");
  for (const char* flag : {"acquire", "max-layers", "coalesce", "budget", "splits", "overlap", "visibility"})
    if (choice.backend != "interp" && args.has(flag))
      fail(std::string("--") + flag, "applies to --backend interp only");
  if (choice.backend != "mvr" && args.has("texture")) fail("--texture", "applies to --backend mvr only");
  const GlPlatform platform = parseGlPlatform(args.get("gl", "auto"));

  // Input problems first, before any GL or file work.
  Scene scene = loadScene(scenePath);
  ShearingCamera camera(cameraFor(scene, width, height), width, height, views, rows);
  auto context = GlContext::create(platform);
  auto renderer = makeRenderer(choice, scene, type);

  if (streaming)
    return streamTo(*renderer, camera, args.get(streamFlag, "-"), type, args.getInt("queue", 8, 1, 4096));

  Manifest layout;
  layout.views = views;
  layout.rows = rows;
  layout.width = width;
  layout.height = height;
  layout.format = format;
  layout.order = order;
  layout.bits = bits;
  ImageSetWriter writer(out, layout);
  // Sink chain: [predistort] -> [reorder] -> writer (+ quilt).
  std::vector<float> lut;
  if (args.has("predistort")) lut = loadPredistortionTable(args.get("predistort", ""), width);
  std::unique_ptr<QuiltSink> quilt;
  if (args.has("quilt")) {
    int qc = 0, qr = 0;
    const std::string q = args.get("quilt", "");
    if (!q.empty() && q != "auto" && std::sscanf(q.c_str(), "%dx%d", &qc, &qr) != 2)
      fail("--quilt", "'" + q + "' is not COLSxROWS");
    if (order != "view") fail("--quilt", "needs --order view");
    quilt = std::make_unique<QuiltSink>(width, height, views, rows, type, qc, qr);
  }
  std::vector<std::unique_ptr<FrameSink>> chain;
  FrameSink* sink = &writer;
  if (quilt) sink = chain.emplace_back(std::make_unique<TeeSink>(std::vector<FrameSink*>{&writer, quilt.get()})).get();
  // Reorder only when the renderer's natural order is not the one asked for.
  if (renderer->order() == FrameOrder::Epi && order == "view")
    sink = chain.emplace_back(std::make_unique<EpisToViews>(*sink, width, height, views, type)).get();
  else if (renderer->order() == FrameOrder::View && order == "epi")
    sink = chain.emplace_back(std::make_unique<ViewsToEpis>(*sink, width, height, views, type)).get();
  if (!lut.empty()) sink = chain.emplace_back(std::make_unique<PredistortSink>(*sink, lut)).get();
  RenderStats stats;
  Stopwatch total;
  renderer->render(camera, *sink, stats);
  sink->finish();
  if (quilt) writer.putExtra(quilt->fileName(format), quilt->quilt());

  Manifest& manifest = writer.manifest();
  nlohmann::json& m = manifest.info;
  m["scene"] = scene.source;
  m["triangles"] = scene.triangleCount();
  m["backend"] = renderer->name();
  if (choice.backend == "mvr" || choice.backend == "interp") m["pst"] = choice.pst;
  m["gl"] = {{"platform", glPlatformName(context->platform())},
             {"version", context->version()},
             {"renderer", context->renderer()}};
  manifest.setCamera(camera);
  m["timings_s"] = stats.times.seconds;
  m["timings_s"]["total"] = total.seconds();
  m["counters"] = stats.counters;
  m["notes"] = stats.notes;
  m["pixel_origin"] = "top-left; view i at camera x = track[0] + i * view_spacing";
  if (quilt) m["quilt"] = quilt->fileName(format);
  if (!lut.empty()) m["predistortion"] = args.get("predistort", "");
  writer.commit();
  std::fprintf(stderr, "mvr: %s rendered %d view(s) of %dx%d to %s in %.3f s\n",
               renderer->name().c_str(), views * rows, width, height, out.c_str(),
               total.seconds());
  return 0;
}

}  // namespace mvr::app
