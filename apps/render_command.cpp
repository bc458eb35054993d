#include "apps/render_command.h"

#include <csignal>
#include <cstdio>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "apps/backend_flags.h"
#include "apps/camera_flags.h"
#include "apps/cli.h"
#include "apps/job_split.h"
#include "apps/memory_check.h"
#include "apps/mpi_session.h"
#include "apps/quilt_layout.h"
#include "apps/split_output.h"
#include "epi/epi_stream.h"
#include "epi/backend.h"
#include "epi/stream_queue.h"
#include "epi/volume.h"
#include "mvr/depth.h"
#include "mvr/error.h"
#include "mvr/frame_sinks.h"
#include "mvr/gl/gl_context.h"
#include "mvr/io/fd_stream.h"
#include "mvr/io/image_codec.h"
#include "mvr/io/image_file.h"
#include "mvr/io/image_set.h"
#include "mvr/io/png_views.h"
#include "mvr/io/rgbd_set.h"
#include "mvr/io/scene_io.h"
#include "mvr/parallel.h"
#include "mvr/progress.h"
#include "mvr/supersampling.h"
#include "shading/shading_plan.h"

namespace mvr::app {

namespace {

// Whether the stream goes to a file written under a temporary name and
// renamed when complete: a regular file, or a path with nothing there yet.
// A device or named pipe (/dev/null, a FIFO a consumer reads) is written
// in place: a rename would replace it with a regular file (as root, even
// /dev/null), and elsewhere its folder is seldom writable.
bool isPlainFile(const std::string& endpoint) {
  if (endpoint == "-" || endpoint.rfind("unix:", 0) == 0 || endpoint.rfind("tcp:", 0) == 0) return false;
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(endpoint, ec);
  return !std::filesystem::exists(status) || std::filesystem::is_regular_file(status);
}

EpiStreamHeader streamHeader(const ShearingCamera& cam, PixelType type, double imagePlaneZ) {
  EpiStreamHeader header{uint32_t(cam.width()), uint32_t(cam.height()), uint32_t(cam.views()),
                         uint32_t(cam.rows()), 4, uint32_t(Image::channelBytes(type)),
                         type == PixelType::Srgb8};
  header.camera = StreamCamera{cam.spec(), imagePlaneZ};
  header.camera->spec.planeHeight = cam.planeHeight();
  return header;
}

// EPIs to a file, stdout or socket as they complete, through a bounded
// queue. A regular file is written under a temporary name and renamed when
// done; a device or named pipe in place (isPlainFile).
int streamTo(Renderer& renderer, const ShearingCamera& cam, double imagePlaneZ, const Supersampling& aa,
             const std::string& endpoint, PixelType type, int queue, const ReorderMemory& memory,
             const std::optional<glm::vec4>& background) {
  namespace fs = std::filesystem;
  std::signal(SIGPIPE, SIG_IGN);  // a vanished consumer is an error, not a kill
  std::signal(SIGXFSZ, SIG_IGN);  // so is a file-size limit
  const bool file = isPlainFile(endpoint);
  const std::string target = file ? endpoint + ".part" : endpoint;
  const EpiStreamHeader header = streamHeader(cam, type, imagePlaneZ);
  Stopwatch watch;
  size_t highWater = 0;
  std::string note;
  std::optional<FdStreamBuf> buffer;
  try {
    buffer.emplace(openForWriting(target));
    std::ostream out(&*buffer);
    QueuedEpiStream stream(out, header, size_t(queue));
    std::unique_ptr<ViewsToEpis> adaptor;
    if (renderer.order() == FrameOrder::View)
      adaptor = std::make_unique<ViewsToEpis>(stream, cam.width(), cam.height(), cam.views(), type,
                                              memory);
    FrameSink* sink = adaptor ? static_cast<FrameSink*>(adaptor.get()) : &stream;
    std::optional<BackgroundSink> over;
    if (background) sink = &over.emplace(*sink, *background);
    std::optional<SupersampleSink> filter;
    if (aa.active()) sink = &filter.emplace(*sink, aa, cam.width(), cam.height(), cam.views());
    const ShearingCamera rendered = aa.active() ? supersampledCamera(cam, aa) : cam;
    ProgressSink progress(*sink, rendered, long(cam.views()) * cam.rows(), renderer.name());
    RenderStats stats;
    renderer.render(rendered, progress, stats);
    progress.finish();
    highWater = stream.highWater();
    if (adaptor) note = adaptor->transpose().scratchNote();
    buffer.reset();  // closed before the rename
  } catch (...) {
    std::error_code ec;
    if (file) fs::remove(target, ec);
    if (buffer && buffer->writeError())  // the system's reason, not the writer's guess
      fail(endpoint, std::string("cannot write stream: ") + std::strerror(buffer->writeError()));
    throw;
  }
  if (file) {
    std::error_code ec;
    fs::rename(target, endpoint, ec);
    if (ec) fail(endpoint, "cannot finish stream file: " + ec.message());
  }
  std::fprintf(stderr, "mvr: streamed %d EPIs of %dx%d to %s in %.3f s (queue high water %zu of %d%s)\n",
               cam.height() * cam.rows(), cam.width(), cam.views(), endpoint.c_str(), watch.seconds(),
               highWater, queue, note.c_str());
  return 0;
}

// Hands each view of the depth pass on as a depth map, from views packed
// one float a pixel (DepthPacker).
class DepthSink final : public FrameSink {
 public:
  explicit DepthSink(ImageSetWriter& writer) : writer_(writer) {}
  void putView(int row, int view, const Image& packed) override { writer_.putDepth(row, view, unpackDepth(packed)); }
  void putEpi(int, int, const Image&) override { fail("--depth", "the depth pass reorders EPIs into views"); }

 private:
  ImageSetWriter& writer_;
};

// The depth scene's frames, views or EPIs, packed into their depths
// (mvr/depth.h) as they come, so that what reorders or exchanges them
// moves 4 bytes a pixel instead of the float colour's 16.
class DepthPacker final : public FrameSink {
 public:
  DepthPacker(FrameSink& inner, const DepthColoring& coloring) : inner_(inner), coloring_(coloring) {}
  void putView(int row, int view, const Image& image) override { inner_.putView(row, view, pack(image)); }
  void putEpi(int row, int scanline, const Image& epi) override { inner_.putEpi(row, scanline, pack(epi)); }
  void finish() override { inner_.finish(); }

 private:
  const Image& pack(const Image& frame) {
    packDepth(frame, coloring_, packed_);
    return packed_;
  }
  FrameSink& inner_;
  DepthColoring coloring_;
  Image packed_;
};

// Runs one phase of the job. In a split job (mpi not null) every rank
// reaches the agreement however its phase ended; when any failed, the
// lowest failing rank has printed its error and every rank stops.
template <class Phase>
void inPhase(MpiSession* mpi, Phase&& phase) {
  if (!mpi) return phase();
  std::string error;
  try {
    phase();
  } catch (const Error& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = std::string("internal error: ") + e.what();
  }
  if (!mpi->agree(error)) throw JobFailed{};
}

// The cameras this process renders: a split job's shares (their samples
// under anti-aliasing), or the whole set.
std::vector<ShearingCamera> rendersOf(const ShearingCamera& rendered, const SplitOutput* split,
                                      const Supersampling& aa) {
  if (!split) return {rendered};
  std::vector<ShearingCamera> renders;
  for (const RenderShare& s : split->shares()) renders.push_back(rendered.withShare(sampleShare(s, aa)));
  return renders;
}

// Renders them into `sink` with progress over the set's `views`, as one
// phase of the job; returns the seconds this process rendered.
double renderPhase(MpiSession* mpi, Renderer& renderer, const std::vector<ShearingCamera>& renders,
                   FrameSink& sink, long views, const std::string& label, RenderStats& stats) {
  Stopwatch watch;
  double seconds = 0.0;
  inPhase(mpi, [&] {
    ProgressSink progress(sink, renders, views, label);
    for (const ShearingCamera& c : renders) renderer.render(c, progress, stats);
    progress.finish();
    seconds = watch.seconds();
  });
  return seconds;
}

// The depth maps: the depth scene (mvr/depth.h) rendered in float by the
// same back end, its EPIs reordered into views where it renders EPIs; in a
// split job each rank renders its shares of the colour pass, and the grid's
// EPIs meet in a scratch file of their own.
void renderDepth(const BackendOptions& choice, const Scene& scene, const ShearingCamera& cam,
                 ImageSetWriter& writer, const ReorderMemory& reorder, RenderStats& stats, MpiSession* mpi,
                 const JobSplit* split, const std::string& dir) {
  DepthColoring coloring;
  Scene depth;  // outlives the renderer, which may keep it
  std::unique_ptr<Renderer> renderer;
  inPhase(mpi, [&] {
    depth = depthScene(scene, cam, coloring);
    renderer = makeRenderer(choice, depth, PixelType::F32);
  });
  DepthSink depthSink(writer);
  std::optional<EpisToViews> reorderer;
  std::optional<SplitOutput> out;
  FrameSink* sink = &depthSink;
  if (split)
    sink = &out.emplace(*mpi, cam, *split,
                        SplitOutputSpec{.rendered = renderer->order(), .type = kPackedDepth, .dir = dir,
                                        .reorder = reorder, .scratchName = ".mvr_split_depth"},
                        depthSink, nullptr)
                .sink();
  else if (renderer->order() == FrameOrder::Epi)
    sink = &reorderer.emplace(depthSink, cam.width(), cam.height(), cam.views(), kPackedDepth, reorder);
  DepthPacker packer(*sink, coloring);
  renderPhase(mpi, *renderer, rendersOf(cam, out ? &*out : nullptr, {}), packer, long(cam.views()) * cam.rows(),
              renderer->name() + ", depth", stats);
  if (out) inPhase(mpi, [&] { out->assemble(); });
}

// The whole stream from a shared file, in order, to a pipe or socket.
void relayStream(SharedFile& records, uint64_t bytes, FdStreamBuf& buffer, const std::string& endpoint) {
  std::ostream out(&buffer);
  std::vector<std::byte> piece;
  for (uint64_t at = 0; at < bytes; at += piece.size()) {
    piece.resize(size_t(std::min<uint64_t>(uint64_t(16) << 20, bytes - at)));
    records.read(at, piece);
    out.write(reinterpret_cast<const char*>(piece.data()), std::streamsize(piece.size()));
    if (!out) break;
  }
  out.flush();
  if (!out || buffer.writeError())
    fail(endpoint, std::string("cannot write stream: ") + std::strerror(buffer.writeError() ? buffer.writeError() : EIO));
}

// The stream of a job split over ranks: every rank writes its EPIs'
// records at their offsets in one shared file, so the stream is the
// single process's byte for byte and no rank holds more than its frames.
// For a plain file that file is the stream (under a temporary name until
// every rank is done); a pipe or socket is fed by rank 0 from a scratch
// file once every rank is done, in stream order.
int streamSplit(MpiSession& mpi, Renderer& renderer, const ShearingCamera& cam, const Supersampling& aa,
                const JobSplit& split, const EpiStreamHeader& header, const std::string& endpoint, const ReorderMemory& reorder,
                const std::optional<glm::vec4>& background) {
  namespace fs = std::filesystem;
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
  const bool file = isPlainFile(endpoint);
  const std::string path = file ? endpoint + ".part" : ".mvr_split_stream";
  const uint64_t bytes = header.recordOffset(cam.rows(), 0);
  Stopwatch watch;
  std::optional<SharedFile> records;
  std::optional<FdStreamBuf> pipe;  // rank 0's, connected before anything is rendered
  inPhase(&mpi, [&] {
    try {
      records.emplace(path, file ? SharedFile::Lifetime::Kept : SharedFile::Lifetime::Scratch);
    } catch (const Error&) {
      if (file) fail(endpoint, "cannot create the stream file");
      throw;
    }
    if (!file && mpi.rank() == 0) pipe.emplace(openForWriting(endpoint));
  });
  try {
    EpiRecordSink sink(header, [&](uint64_t at, std::span<const std::byte> b) { records->write(at, b); });
    SplitOutput out(mpi, cam, split,
                    SplitOutputSpec{.rendered = renderer.order(), .toViews = false, .type = header.pixelType(),
                                    .dir = ".", .reorder = reorder},
                    sink, nullptr);
    FrameSink* frames = &out.sink();
    std::optional<BackgroundSink> over;
    if (background) frames = &over.emplace(*frames, *background);
    std::optional<SupersampleSink> filter;
    if (aa.active()) frames = &filter.emplace(*frames, aa, cam.width(), cam.height(), cam.views());
    const ShearingCamera rendered = aa.active() ? supersampledCamera(cam, aa) : cam;
    inPhase(&mpi, [&] {
      if (mpi.rank() != 0) return;
      const std::vector<uint8_t> head = header.encode();
      records->write(0, std::as_bytes(std::span(head)));
    });
    RenderStats stats;
    renderPhase(&mpi, renderer, rendersOf(rendered, &out, aa), *frames, long(cam.views()) * cam.rows(),
                renderer.name(), stats);
    inPhase(&mpi, [&] { out.assemble(); });
    if (!file) inPhase(&mpi, [&] { if (pipe) relayStream(*records, bytes, *pipe, endpoint); });
    records.reset();  // collective; a kept file is complete
    if (file) inPhase(&mpi, [&] {
      std::error_code ec;
      if (mpi.rank() == 0) fs::rename(path, endpoint, ec);
      if (ec) fail(endpoint, "cannot finish stream file: " + ec.message());
    });
  } catch (...) {
    records.reset();  // every rank is here: phases end on every rank alike
    std::error_code ec;
    if (file && mpi.rank() == 0) fs::remove(path, ec);
    throw;
  }
  if (mpi.rank() == 0)
    std::fprintf(stderr, "mvr: streamed %d EPIs of %dx%d to %s in %.3f s with %d ranks\n", cam.height() * cam.rows(),
                 cam.width(), cam.views(), endpoint.c_str(), watch.seconds(), mpi.ranks());
  return 0;
}

}  // namespace

namespace {

// The options render and stream share, and each command's own.
struct RenderFlags {
  BackendFlags backend;
  std::string scene;
  int views = 16, rows = 1, queue = 8, compression = kDefaultPngCompression;
  std::optional<int> bits;  // unset: 8 for png and tiff, 32 (float) for exr
  std::pair<int, int> size{320, 240};
  std::string out = "out", format = "png", order = "view", gl = "auto";
  std::string stream, quilt, predistort, codec;
  bool strict = false, linear = false, depth = false, quiltOnly = false;
  std::string splitBy = "cost";  // under mpirun: scanline bands by estimated cost or by count
  MemoryFlags memory;
  std::string from;  // synthesize: the references' folder
  std::string warpPath;  // synthesize: WarpOptions::path by name
  WarpOptions warp;
  CameraFlags camera;
  Supersampling aa;

  void addShared(CLI::App& app) {
    app.add_option("SCENE", scene,
                   "a JSON scene file or a mesh (OBJ, PLY, OFF, STL); default: the bundled scene");
    backend.add(app);
    addOutputShape(app);
  }

  void addOutputShape(CLI::App& app) {
    addViewCountOptions(app, views, rows);
    addSizeOption(app, "size", size, "image size in pixels");
    camera.add(app);
    addAntialiasingOptions(app, aa);
    app.add_option("--format", format, "image format: png, exr or tiff (exr renders in float)")
        ->capture_default_str();
    addGlOption(app, gl);
    addThreadsOption(app);
    if (!app.get_option_no_throw("--from")) addStrictOption(app, strict);
    app.add_flag("--linear", linear,
                 "write linear values to png and tiff files (and 8-bit streams) instead of "
                 "sRGB-encoded ones; exr is always linear");
  }

  void addRenderOwn(CLI::App& app) {
    app.add_option("--out", out, "output folder")->capture_default_str();
    app.add_option("--order", order, "write views (view_*) or EPIs (epi_*)")
        ->check(CLI::IsMember({"view", "epi"}))
        ->capture_default_str();
    app.add_option("--bits", bits,
                   "bits per channel: png and tiff 8 (default) or 16, exr 16 (half) or 32 (float, "
                   "default); anything but 8 renders in float")
        ->check(CLI::IsMember({8, 16, 32}));
    app.add_option("--compression", compression,
                   "png compression, 0 (stored) to 9 (smallest): 1 is mvr's row coder (the Up "
                   "filter: 1.5x the speed of zlib's level 1 on rendered views for files 6% "
                   "larger, 13x level 6's for 55% larger), 2-9 are zlib's levels, with no row "
                   "filter at 2-3 and libpng's adaptive filters at 4-9")
        ->check(CLI::Range(0, 9))
        ->capture_default_str();
    app.add_option("--codec", codec,
                   "codec of exr files (none, rle, zip, zips, piz, pxr24, b44, dwaa, dwab) or tiff "
                   "files (none, lzw, zip); default zip")
        ->type_name("NAME");
    app.add_option("--quilt", quilt,
                   "also write all views tiled in one quilt image, quilt_qs{C}x{R}a{aspect}.{format}, "
                   "with its layout in EXIF UserComment (auto: near square; a display preset sets the "
                   "views and tile size: go, portrait, 16-landscape, 16-portrait, 32-landscape, "
                   "32-portrait, 65)")
        ->type_name("auto|CxR|DISPLAY");
    app.add_flag("--quilt-only", quiltOnly, "write the quilt (and manifest) without the view images");
    app.add_flag("--depth", depth,
                 "also write each view's depth map, depth_0000.exr (one float channel Z): the "
                 "distance along the view axis in world units, 0 where nothing is seen; the same "
                 "back end renders the scene a second time");
    app.add_option("--predistort", predistort,
                   "resample every row through a table of source x per column (docs/CONVENTIONS.md)")
        ->type_name("LUT");
    app.add_option("--stream", stream,
                   "write the raw EPI-major stream (docs/EPI_STREAM.md) to a file or stdout "
                   "instead of an image set (see mvr stream)")
        ->type_name("PATH|-");
    memory.add(app, "the output folder; the current folder with --stream");
    app.add_option("--split-by", splitBy,
                   "under mpirun: cut a row into scanline bands of equal estimated cost (slices per "
                   "scanline plus a fixed part) or of equal scanline count")
        ->check(CLI::IsMember({"cost", "count"}))
        ->capture_default_str();
  }

  // synthesize: references instead of a scene, the warp back end's options.
  void addSynthesizeOwn(CLI::App& app) {
    app.add_option("--from", from,
                   "RGB-D references: a set mvr render --depth wrote, or the HCI 4D light-field "
                   "layout (parameters.cfg, input_Cam%03d.png, gt_depth_lowres[_Cam%03d].pfm)")
        ->required();
    app.add_option("--tau", warp.tau, "relative depth step of a discontinuity and of a nearer surface")
        ->capture_default_str();
    app.add_option("--penalty", warp.penalty, "growth a of the occlusion penalty (seed eq. 5-2)")
        ->type_name("A")
        ->capture_default_str();
    app.add_option("--flatness", warp.flatness,
                   "by GL: merge grid cells into one quad where that moves no vertex more than PX pixels in "
                   "the farthest view (0: only planes merge)")
        ->type_name("PX")
        ->capture_default_str();
    app.add_option("--warp-path", warpPath,
                   "by GL, the seed's grid mesh (gl), or on the CPU, EPI by EPI, exactly (cpu: the references on "
                   "the rows of views, as their own track puts them); auto (default): cpu where GL renders on "
                   "the CPU (llvmpipe) and it can, else gl")
        ->type_name(choices(kWarpPathNames));
  }

  void addStreamOwn(CLI::App& app) {
    app.add_option("--to", stream, "where the stream goes")
        ->type_name("-|FILE|unix:PATH|tcp:HOST:PORT")
        ->required();
    app.add_option("--queue", queue, "EPIs held at most")
        ->check(CLI::Range(1, 4096))
        ->capture_default_str();
    memory.add(app, "the current folder");
  }
};

}  // namespace

int runRender(int argc, char** argv, RenderCommand command) {
  const bool streamCommand = command == RenderCommand::Stream, synthesize = command == RenderCommand::Synthesize;
  CLI::App app(streamCommand
                   ? "Renders like mvr render and sends each EPI as it completes in the raw "
                     "EPI-major stream (docs/EPI_STREAM.md). Sockets connect to a listening "
                     "consumer (mvr-consume). A bounded queue decouples rendering from sending; "
                     "when the consumer is slow the renderer waits (backpressure)."
                   : synthesize
                   ? "Renders a shearing-camera track or grid from RGB-D references with the depth-image "
                     "warping back end (each view from its two nearest references), to the outputs "
                     "mvr render writes. Views, rows and size default to the references' own grid."
                   : "Renders a scene's views with one back end to an image set.",
               streamCommand ? "mvr stream" : synthesize ? "mvr synthesize" : "mvr render");
  RenderFlags f;
  if (synthesize) {
    f.addSynthesizeOwn(app);
    f.addOutputShape(app);
  } else {
    f.addShared(app);
  }
  if (streamCommand) f.addStreamOwn(app);
  else f.addRenderOwn(app);
  if (!streamCommand)
    app.footer("Writes view_0000.png ... (view_r000_c0000.png for grids) and manifest.json.");
  if (auto exit = parseCommandLine(app, argc - 1, argv + 1)) return *exit;

  BackendOptions choice = synthesize ? BackendOptions{.backend = Backend::Warp} : f.backend.resolve();
  f.camera.validate();
  if (synthesize) {
    if (!f.warpPath.empty()) f.warp.path = parseName(kWarpPathNames, f.warpPath, "--warp-path", "path");
    validate(f.warp);
    if (f.depth) fail("--depth", "mvr synthesize writes colour only");
    if (!f.camera.focal.empty()) fail("--focal", "the references fix the display plane");
  }
  const bool streaming = !f.stream.empty();
  const std::string scenePath = f.scene.empty() ? defaultScenePath() : f.scene;
  // A display's quilt preset sets the views and the tile size unless given.
  std::optional<QuiltLayout> quiltLayout;
  if (f.quiltOnly && f.quilt.empty()) f.quilt = "auto";
  if (f.quiltOnly && (f.depth || streaming)) fail("--quilt-only", "writes a quilt: not with --depth or --stream");
  if (!f.quilt.empty()) {
    quiltLayout = parseQuilt(f.quilt);
    if (!quiltLayout->preset.empty()) {
      if (!app.count("--views")) f.views = quiltLayout->columns * quiltLayout->rows;
      if (!app.count("--size")) f.size = {quiltLayout->tileWidth(), quiltLayout->tileHeight()};
    }
  }
  // The references first: their grid is synthesize's default track and size.
  std::optional<RgbdSet> references;
  if (synthesize) {
    references = loadRgbdSet(f.from);
    if (!app.count("--views")) f.views = references->views;
    if (!app.count("--rows")) f.rows = references->rows;
    if (!app.count("--size")) f.size = {references->width, references->height};
  }
  const int views = f.views, rows = f.rows, bits = f.bits.value_or(defaultBits(f.format));
  const auto [width, height] = f.size;
  const std::string &out = f.out, &format = f.format, &order = f.order;
  // 8-bit PNG renders into 8-bit targets, sRGB-encoding ones unless
  // --linear (encoded from full precision, not from 8-bit linear values);
  // everything else renders in float and is encoded as it is written.
  const PixelType type = format == "png" && bits == 8 ? (f.linear ? PixelType::U8 : PixelType::Srgb8)
                                                      : PixelType::F32;
  const GlPlatform platform = parseGlPlatform(f.gl);
  if (f.depth && (streaming || order != "view" || !f.predistort.empty()))
    fail("--depth", "writes a view set: not with --stream, --order epi or --predistort");
  // Under mpirun the ranks share the job (apps/job_split.h); rank 0 reports.
  MpiSession* const mpi = MpiSession::current();
  if (mpi) {
    if (mpi->rank() != 0) setProgressEnabled(false);
  }

  // OpenImageIO (about 260 libraries) loads beside the scene's loading,
  // for the files PNG is not (mvr/io/png_encoder.h writes PNGs). Not later:
  // dlopen holds the dynamic loader's lock, which GL start-up (its driver),
  // the pool's start-up and llvmpipe's shader compiler (its symbol
  // lookups) all take, so whatever runs beside the load waits for it
  // unless it is pure computation like reading the scene. Started after
  // GL, a one-view render took 0.78-0.82 s against 0.69-0.70 s.
  startPool();
  // Depth maps of the default codec are our own encoder's (mvr/io/exr_depth.h).
  if (!streaming && (format != "png" || (f.depth && !ownsDepthCodec(f.codec)))) preloadImageCodec();
  // Where start-up time goes, in the manifest (issue 15).
  StageTimes startup;
  Stopwatch sinceStart;
  // The scene loads on a worker while GL starts here (a context belongs to
  // the thread that made it): 143K triangles take 0.13 s, GL 0.08 s.
  auto loading = std::async(std::launch::async, [&] {
    const Stopwatch watch;
    Scene loaded = synthesize ? Scene{} : loadInputScene(scenePath, f.strict);
    return std::pair{std::move(loaded), watch.seconds()};
  });
  std::unique_ptr<GlContext> context;
  try {
    context = GlContext::create(platform);
  } catch (...) {
    (void)loading.get();  // input problems first: the scene's error, if it has one
    throw;
  }
  startup.add("gl", sinceStart.seconds());
  auto [scene, sceneSeconds] = loading.get();
  if (!synthesize) f.backend.chooseDefaultPst(choice, scene);
  startup.add("scene", sceneSeconds);
  Stopwatch phase;
  if (const shading::ShadingPlan plan = shading::planShading(scene); plan.texture || plan.reflection)
    preloadImageCodec();  // a stream of a textured scene reads images too
  const double imagePlaneZ = f.camera.placeFocalPlane(scene);
  CameraSpec spec = synthesize ? references->camera : cameraFor(scene, width, height);
  if (synthesize && (width != references->width || height != references->height))
    spec.planeHeight = 0.0;  // another size: the image plane's height from its aspect
  spec = f.camera.adjust(spec, width, height);
  if (quiltLayout && quiltLayout->aspect > 0.0) {
    // The display stretches the tiles to its aspect: the plane has it.
    spec.planeHeight = spec.planeWidth / quiltLayout->aspect;
  }
  ShearingCamera camera(spec, width, height, views, rows);
  if (f.aa.views > 1 && views < 2) fail("--aa-views", "needs at least 2 views: one view has no track to sample");
  // Anti-aliasing: the back end renders the samples, a sink filters them.
  const ShearingCamera renderCamera = f.aa.active() ? supersampledCamera(camera, f.aa) : camera;
  const size_t referenceCount = synthesize ? references->references.size() : 0;
  auto renderer = synthesize ? makeWarpRenderer(std::move(references->references), type, f.warp, &renderCamera)
                             : makeRenderer(choice, scene, type);
  startup.add("renderer", phase.restart());
  // Frames held, decided before rendering starts: a reordering sink's row
  // within the memory budget (beyond it, a scratch file), a quilt whole.
  const size_t pixelBytes = 4 * Image::channelBytes(type);
  const size_t viewBytes = size_t(width) * height * pixelBytes, rowBytes = viewBytes * views;
  const bool reorders = streaming ? renderer->order() == FrameOrder::View
                                  : (renderer->order() == FrameOrder::Epi) == (order == "view");
  ReorderMemory reorder;
  if (reorders) {
    // The frames the sink hands on, and how many its consumer holds in flight.
    const bool toViews = !streaming && order == "view";
    reorder = f.memory.reorder(toViews ? viewBytes : size_t(width) * views * pixelBytes,
                               streaming ? f.queue : BoundedTasks::defaultLimit(),
                               streaming ? "." : out);
  }
  // 8-bit PNG views from EPIs take each EPI's rows into their encoders and
  // hold the files' bytes (within the budget, beyond it on their way to
  // disk), no volume: what is left to reorder through a scratch file is
  // the rest.
  const Manifest setManifest{.views = views, .rows = rows, .width = width, .height = height, .format = format,
                          .order = order, .bits = bits, .compression = f.compression, .codec = f.codec,
                          .srgb = !f.linear};
  const size_t pngFilesBudget = EpisToPngViews::filesBudget(setManifest, type, reorder.budget);
  const bool pngRows = reorders && !streaming && !mpi && order == "view" && !quiltLayout &&
                       EpisToPngViews::handles(setManifest, type) && pngFilesBudget > 0;
  const bool scratch = reorders && !pngRows && reorder.spills(rowBytes);
  // The depth pass reorders its packed frames (mvr/depth.h) where the back end renders EPIs.
  const size_t depthViewBytes = size_t(width) * height * 4 * Image::channelBytes(kPackedDepth);
  const size_t depthRowBytes = depthViewBytes * views;
  ReorderMemory depthReorder;
  const bool depthReorders = f.depth && renderer->order() == FrameOrder::Epi;
  if (depthReorders) depthReorder = f.memory.reorder(depthViewBytes, BoundedTasks::defaultLimit(), out);
  checkHeldFramesFit({.reorderBytes = std::max(reorders ? reorder.held(rowBytes) : 0,
                                               depthReorders ? depthReorder.held(depthRowBytes) : 0),
                      .quiltBytes = !streaming && !f.quilt.empty() && (!mpi || mpi->rank() == 0) ? rowBytes * rows : 0},
                     availableMemory(),
                     std::string("give a smaller --memory") + (f.quilt.empty() ? "" : ", drop --quilt") +
                         ", fewer views or a smaller size");
  if (scratch && streaming) checkScratchFits(rowBytes, reorder.scratchDir);

  const std::optional<glm::vec4> background = f.camera.backgroundColor();
  // Under mpirun: the same on every rank (apps/job_split.h).
  auto splitFor = [&] {
    return splitJob(camera, renderer->order(), mpi->ranks(),
                    synthesize || f.splitBy == "count" ? std::vector<double>{}
                                                       : scanlineCosts(scene, camera, rows / 2));
  };
  if (streaming && mpi) {
    const JobSplit jobSplit = splitFor();
    const EpiStreamHeader header = streamHeader(camera, type, imagePlaneZ);
    // The grid's views meet in a scratch file; a pipe's records in another.
    const uint64_t streamBytes = header.recordOffset(rows, 0);
    checkScratchFits((reorders && jobSplit.gridBegin() < rows ? rowBytes * rows : 0) +
                         (isPlainFile(f.stream) ? 0 : streamBytes), ".");
    if (!mpi->agree("")) throw JobFailed{};
    return streamSplit(*mpi, *renderer, camera, f.aa, jobSplit, header, f.stream, reorder, background);
  }
  if (streaming) return streamTo(*renderer, camera, imagePlaneZ, f.aa, f.stream, type, f.queue, reorder, background);

  ImageSetWriter writer(out, setManifest);
  // Sink chain: [predistort] -> [reorder] -> writer (+ quilt).
  if (scratch) checkScratchFits(rowBytes, reorder.scratchDir);  // the output folder exists now
  if (depthReorders && depthReorder.spills(depthRowBytes)) checkScratchFits(depthRowBytes, depthReorder.scratchDir);
  std::vector<float> lut;
  if (!f.predistort.empty()) lut = loadPredistortionTable(f.predistort, width);
  std::unique_ptr<QuiltSink> quilt;
  if (quiltLayout && (!mpi || mpi->rank() == 0)) {
    if (order != "view") fail("--quilt", "needs --order view");
    quilt = std::make_unique<QuiltSink>(width, height, views, rows, type, quiltLayout->columns, quiltLayout->rows);
    if (const long tiles = long(quilt->columns()) * quilt->tileRows(); tiles > long(views) * rows)
      std::fprintf(stderr, "mvr: warning: the %dx%d quilt leaves %ld of its tiles empty\n", quilt->columns(),
                   quilt->tileRows(), tiles - long(views) * rows);
  }
  std::vector<std::unique_ptr<FrameSink>> chain;
  FrameSink* sink = &writer;
  const FrameTranspose* transpose = nullptr;
  const EpisToPngViews* pngViews = nullptr;
  std::optional<SplitOutput> split;
  if (mpi) {
    // Set-up is done on every rank once they agree; then each renders its share.
    const JobSplit jobSplit = splitFor();
    // The shared files: the colour's and the depth's, which lives after it.
    const bool exchanges = reorders && jobSplit.gridBegin() < rows;
    const size_t shared = (quiltLayout || exchanges ? rowBytes * rows : 0) +
                          (depthReorders && jobSplit.gridBegin() < rows ? depthRowBytes * rows : 0);
    if (shared > 0) checkScratchFits(shared, out);
    if (!mpi->agree("")) throw JobFailed{};
    split.emplace(*mpi, camera, jobSplit,
                  SplitOutputSpec{.rendered = renderer->order(), .toViews = order == "view", .type = type,
                                  .dir = out, .quilt = quiltLayout.has_value(), .frames = !f.quiltOnly,
                                  .reorder = reorder},
                  writer, quilt.get());
    sink = &split->sink();
  } else {
    if (quilt && f.quiltOnly) sink = quilt.get();
    else if (quilt) sink = chain.emplace_back(std::make_unique<TeeSink>(std::vector<FrameSink*>{&writer, quilt.get()})).get();
    // Reorder only when the renderer's natural order is not the one asked for.
    if (renderer->order() == FrameOrder::Epi && order == "view") {
      if (pngRows) {
        // A queue lets a GL renderer draw while the pool encodes; the CPU
        // span back end renders on that pool, so a long queue only holds memory.
        const bool onPool = choice.hasPst() && choice.pst() == PstMode::Cpu;
        auto views = std::make_unique<EpisToPngViews>(
            writer, type, pngFilesBudget, onPool ? 4 : EpisToPngViews::queueLength(setManifest, type, reorder.budget));
        pngViews = views.get();
        sink = chain.emplace_back(std::move(views)).get();
      } else {
        auto reorderer = std::make_unique<EpisToViews>(*sink, width, height, views, type, reorder);
        transpose = &reorderer->transpose();
        sink = chain.emplace_back(std::move(reorderer)).get();
      }
    } else if (renderer->order() == FrameOrder::View && order == "epi") {
      auto reorderer = std::make_unique<ViewsToEpis>(*sink, width, height, views, type, reorder);
      transpose = &reorderer->transpose();
      sink = chain.emplace_back(std::move(reorderer)).get();
    }
  }
  // Per pixel: the same bytes before or after a reorder.
  if (background) sink = chain.emplace_back(std::make_unique<BackgroundSink>(*sink, *background)).get();
  if (!lut.empty()) sink = chain.emplace_back(std::make_unique<PredistortSink>(*sink, lut)).get();
  if (f.aa.active())
    sink = chain.emplace_back(std::make_unique<SupersampleSink>(*sink, f.aa, width, height, views)).get();
  RenderStats stats;
  startup.add("before_render", sinceStart.seconds());
  Stopwatch total;
  const std::string label = renderer->name() + (choice.hasPst() ? std::string(" ") + pstModeName(choice.pst()) : "");
  // This process's, before waiting for the others.
  const double renderSeconds = renderPhase(mpi, *renderer, rendersOf(renderCamera, split ? &*split : nullptr, f.aa),
                                           *sink, long(views) * rows, label, stats);
  const double quiltAspect = quiltLayout && quiltLayout->aspect > 0.0 ? quiltLayout->aspect : double(width) / height;
  inPhase(mpi, [&] {
    if (split) split->assemble();
    if (quilt)
      writer.putExtra(quilt->fileName(format, quiltAspect), quilt->quilt(),
                      {{"Exif:UserComment",
                        quiltMetadata(views * rows, quilt->columns(), quilt->tileRows(), quiltAspect)}});
    if (mpi) writer.flush();
  });
  const double colorSeconds = total.seconds();
  RenderStats depthStats;
  if (f.depth)
    renderDepth(choice, scene, camera, writer, depthReorder, depthStats, mpi, split ? &split->split() : nullptr, out);
  writer.flush();  // every image encoded, so the module's load is done and timed

  Manifest& manifest = writer.manifest();
  nlohmann::json& m = manifest.info;
  if (synthesize) {
    m["references"] = {{"from", f.from}, {"layout", references->layout}, {"count", referenceCount},
                       {"tau", f.warp.tau}, {"penalty", f.warp.penalty}};
  } else {
    m["scene"] = scene.source;
    m["triangles"] = scene.triangleCount();
  }
  m["backend"] = renderer->name();
  if (choice.hasPst()) m["pst"] = pstModeName(choice.pst());
  m["gl"] = {{"platform", glPlatformName(context->platform())},
             {"version", context->version()},
             {"renderer", context->renderer()}};
  manifest.setCamera(camera, imagePlaneZ);
  if (f.aa.active())
    m["antialiasing"] = {{"filter", "box, in linear light, colour weighted by alpha"},
                         {"samples_per_pixel", f.aa.spatial * f.aa.spatial},
                         {"samples_per_view", f.aa.views},
                         {"depth", "not filtered: depth maps sample pixel centres"}};
  if (background) m["background"] = {(*background).r, (*background).g, (*background).b, (*background).a};
  m["timings_s"] = stats.times.seconds;
  m["timings_s"]["total"] = total.seconds();
  if (const double load = imageCodecLoadSeconds(); load > 0.0) startup.add("image_module_load", load);
  m["startup_s"] = startup.seconds;
  m["counters"] = stats.counters;
  m["notes"] = stats.notes;
  m["pixel_origin"] = "top-left; view i at camera x = track[0] + i * view_spacing";
  if (quilt) {
    m["quilt"] = quilt->fileName(format, quiltAspect);
    m["quilt_layout"] = {{"columns", quilt->columns()},
                         {"rows", quilt->tileRows()},
                         {"aspect", quiltAspect},
                         {"order", rows > 1 ? "grid row 0 at the top, views left to right"
                                            : "view 0 at the bottom left, left to right, then upwards"}};
    if (!quiltLayout->preset.empty()) m["quilt_layout"]["preset"] = quiltLayout->preset;
  }
  if (transpose)
    m["reorder"] = {{"method", transpose->method()},
                    {"budget_bytes", reorder.budget},
                    {"scratch_file", transpose->usesScratch()},
                    {"frames_per_pass", transpose->outputsPerPass()}};
  if (pngViews)
    m["reorder"] = {{"method", EpisToPngViews::kMethod},
                    {"budget_bytes", reorder.budget},
                    {"scratch_file", false},
                    {"files_to_disk_before_done", pngViews->spills()}};
  if (!lut.empty()) m["predistortion"] = f.predistort;
  if (f.depth) {
    m["timings_s"]["color"] = colorSeconds;
    m["depth"] = {{"files", manifest.depthPattern() + ".exr"},
                  {"channel", "Z"},
                  {"measure", "distance along the view axis (camera z of V in cameras), world units"},
                  {"background", 0},
                  {"timings_s", depthStats.times.seconds}};
  }
  if (split) {
    m["mpi"] = split->info();
    m["mpi"]["split_by"] = f.splitBy;
    std::vector<double> seconds;  // every rank's rendering, in rank order
    for (const std::string& t : mpi->gatherAtRoot({std::to_string(renderSeconds)})) seconds.push_back(std::stod(t));
    m["mpi"]["render_s"] = seconds;
    // Rank 0 writes the manifest, counting every rank's files as the set's.
    const std::vector<std::string> names = mpi->gatherAtRoot(writer.writtenNames());
    inPhase(mpi, [&] {
      if (mpi->rank() == 0) writer.commit(names);
    });
    writer.keep();
    if (mpi->rank() != 0) return 0;
  } else {
    writer.commit();
  }
  std::fprintf(stderr, "mvr: rendered %d view%s of %dx%d with %s to %s in %.3f s%s\n", views * rows,
               views * rows == 1 ? "" : "s", width, height, label.c_str(), out.c_str(), total.seconds(),
               transpose ? transpose->scratchNote().c_str() : "");
  return 0;
}

}  // namespace mvr::app
