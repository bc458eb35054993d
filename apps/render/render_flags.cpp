#include "apps/render/render_flags.h"

#include "apps/cli/cli.h"
#include "mvr/error.h"
#include "mvr/images/panel_calibration.h"
#include "mvr/assets/scene_io.h"

namespace mvr::app {

std::string RenderFlags::description() const {
  switch (command_) {
    case RenderCommand::Stream:
      return "Renders like mvr render and sends each EPI as it completes in the raw "
             "EPI-major stream (docs/EPI_STREAM.md). Sockets connect to a listening "
             "consumer (mvr-consume). A bounded queue decouples rendering from sending; "
             "when the consumer is slow the renderer waits (backpressure).";
    case RenderCommand::Synthesize:
      return "Renders a shearing-camera track or grid from RGB-D references with the depth-image "
             "warping back end (each view from its two nearest references), to the outputs "
             "mvr render writes. Views, rows and size default to the references' own grid.";
    case RenderCommand::Render:
      break;
  }
  return "Renders a scene's views with one back end to an image set.";
}

std::string RenderFlags::name() const {
  switch (command_) {
    case RenderCommand::Stream: return "mvr stream";
    case RenderCommand::Synthesize: return "mvr synthesize";
    case RenderCommand::Render: break;
  }
  return "mvr render";
}

void RenderFlags::add(CLI::App& app) {
  if (command_ == RenderCommand::Synthesize) {
    addSynthesizeOwn(app);
    addOutputShape(app);
  } else {
    addShared(app);
  }
  if (command_ == RenderCommand::Stream) {
    addStreamOwn(app);
  } else {
    addRenderOwn(app);
    app.footer("Writes view_0000.png ... (view_r000_c0000.png for grids) and manifest.json.");
  }
}

void RenderFlags::addShared(CLI::App& app) {
  app.add_option("SCENE", scene_, "a JSON scene file or a model (glTF, GLB, OBJ with its MTL, PLY, OFF, STL); default: the bundled scene");
  backend_.add(app);
  addOutputShape(app);
}

void RenderFlags::addOutputShape(CLI::App& app) {
  addViewCountOptions(app, views_, rows_);
  addSizeOption(app, "size", size_, "image size in pixels");
  camera_.add(app);
  addAntialiasingOptions(app, aa_);
  app.add_option("--format", format_, "image format: png, exr or tiff (exr renders in float)")->capture_default_str();
  addGlOption(app, gl_);
  addThreadsOption(app);
  if (!app.get_option_no_throw("--from")) {
    addStrictOption(app, strict_);
    addLookOptions(app, look_);
    addToneMapOption(app, tonemap_);
  }
  app.add_flag("--linear", linear_,
               "write linear values to png and tiff files (and 8-bit streams) instead of "
               "sRGB-encoded ones; exr is always linear");
}

void RenderFlags::addRenderOwn(CLI::App& app) {
  app.add_option("--out", out_, "output folder")->capture_default_str();
  app.add_option("--order", order_, "write views (view_*) or EPIs (epi_*)")
      ->check(CLI::IsMember({"view", "epi"}))
      ->capture_default_str();
  app.add_option("--bits", bits_,
                 "bits per channel: png and tiff 8 (default) or 16, exr 16 (half) or 32 (float, "
                 "default); anything but 8 renders in float")
      ->check(CLI::IsMember({8, 16, 32}));
  app.add_option("--compression", compression_,
                 "png compression, 0 (stored) to 9 (smallest): 1 is mvr's row coder (the Up "
                 "filter: 1.5x the speed of zlib's level 1 on rendered views for files 6% "
                 "larger, 13x level 6's for 55% larger), 2-9 are zlib's levels, with no row "
                 "filter at 2-3 and libpng's adaptive filters at 4-9")
      ->check(CLI::Range(0, 9))
      ->capture_default_str();
  app.add_option("--codec", codec_,
                 "codec of exr files (none, rle, zip, zips, piz, pxr24, b44, dwaa, dwab) or tiff "
                 "files (none, lzw, zip); default zip")
      ->type_name("NAME");
  app.add_option("--quilt", quilt_,
                 "also write all views tiled in one quilt image, quilt_qs{C}x{R}a{aspect}.{format}, "
                 "with its layout in EXIF UserComment (auto: near square; a display preset sets the "
                 "views and tile size: go, portrait, 16-landscape, 16-portrait, 32-landscape, "
                 "32-portrait, 65)")
      ->type_name("auto|CxR|DISPLAY");
  app.add_flag("--quilt-only", quiltOnly_, "write the quilt (and manifest) without the view images");
  app.add_option("--native", native_,
                 "with --quilt: also write the lenticular display's native image of the quilt, "
                 "native_{W}x{H}.png, by the display's calibration (Looking Glass's visual.json; "
                 "docs/DISPLAY.md); with --video, its video too")
      ->type_name("CALIBRATION");
  app.add_flag("--depth", depth_,
               "also write each view's depth map, depth_0000.exr (one float channel Z): the "
               "distance along the view axis in world units, 0 where nothing is seen; the same "
               "back end renders the scene a second time");
  app.add_option("--predistort", predistort_,
                 "resample every row through a table of source x per column (docs/CONVENTIONS.md)")
      ->type_name("LUT");
  app.add_option("--stream", stream_,
                 "write the raw EPI-major stream (docs/EPI_STREAM.md) to a file or stdout "
                 "instead of an image set (see mvr stream)")
      ->type_name("PATH|-");
  memory_.add(app, "the output folder; the current folder with --stream");
  app.add_option("--split-by", splitBy_,
                 "under mpirun: cut a row into scanline bands of equal estimated cost (slices per "
                 "scanline plus a fixed part) or of equal scanline count")
      ->check(CLI::IsMember({"cost", "count"}))
      ->capture_default_str();
  if (command_ == RenderCommand::Render) sequence_.add(app);  // references do not move
}

// synthesize: references instead of a scene, the warp back end's options.
void RenderFlags::addSynthesizeOwn(CLI::App& app) {
  app.add_option("--from", from_,
                 "RGB-D references: a set mvr render --depth wrote, or the HCI 4D light-field "
                 "layout (parameters.cfg, input_Cam%03d.png, gt_depth_lowres[_Cam%03d].pfm)")
      ->required();
  // warp's numbers but the source budget and outline: captured references
  // are given, not chosen, and have no finer outline.
  for (const NumberOption<WarpOptions>& n : kWarpNumbers)
    if (std::string(n.flag) != "--budget" && std::string(n.flag) != "--outline-samples") addNumber(app, n, warp_);
  app.add_option("--warp-path", warpPath_,
                 "by GL, the seed's grid mesh (gl), or on the CPU, EPI by EPI, exactly (cpu: the references on "
                 "the rows of views, as their own track puts them); auto (default): cpu where GL renders on "
                 "the CPU (llvmpipe) and it can, else gl")
      ->type_name(choices(kWarpPathNames));
}

void RenderFlags::addStreamOwn(CLI::App& app) {
  app.add_option("--to", stream_, "where the stream goes")->type_name("-|FILE|unix:PATH|tcp:HOST:PORT")->required();
  app.add_option("--queue", queue_, "EPIs held at most")->check(CLI::Range(1, 4096))->capture_default_str();
  memory_.add(app, "the current folder");
  sequence_.add(app, true);
}

RenderJob RenderFlags::describe(const CLI::App& app) const {
  RenderJob job;
  job.command = command_;
  const bool synthesize = job.synthesize();
  job.backendFlags = backend_;
  job.backend = synthesize ? BackendOptions{.backend = Backend::Warp} : backend_.resolve();
  job.camera = camera_;
  job.camera.validate();
  job.warp = warp_;
  if (synthesize) {
    if (!warpPath_.empty()) job.warp.path = parseName(kWarpPathNames, warpPath_, "--warp-path", "path");
    validate(job.warp);
    if (depth_) fail("--depth", "mvr synthesize writes colour only");
    if (!camera_.focal.empty()) fail("--focal", "the references fix the display plane");
  }
  job.stream = stream_;
  job.scenePath = scene_.empty() ? defaultScenePath() : scene_;
  job.views = views_, job.rows = rows_;
  std::tie(job.width, job.height) = size_;
  // A display's quilt preset sets the views and the tile size unless given.
  const std::string quilt = quiltOnly_ && quilt_.empty() ? "auto" : quilt_;
  if (quiltOnly_ && (depth_ || job.streaming())) fail("--quilt-only", "writes a quilt: not with --depth or --stream");
  if (!quilt.empty()) {
    job.quilt = parseQuilt(quilt);
    if (!job.quilt->preset.empty()) {
      if (!app.count("--views")) job.views = job.quilt->columns * job.quilt->rows;
      if (!app.count("--size")) job.width = job.quilt->tileWidth(), job.height = job.quilt->tileHeight();
    }
  }
  // The references first: their grid is synthesize's default track and size.
  if (synthesize) {
    job.from = from_;
    job.references = loadRgbdSet(from_);
    if (!app.count("--views")) job.views = job.references->views;
    if (!app.count("--rows")) job.rows = job.references->rows;
    if (!app.count("--size")) job.width = job.references->width, job.height = job.references->height;
  }
  job.strict = strict_;
  job.look = look_;
  job.toneMap = *toneMapNamed(tonemap_);
  if (job.toneMap != ToneMap::None && format_ == "exr") fail("--tonemap", "exr keeps linear radiance: not with --format exr");
  job.out = out_, job.format = format_, job.order = order_;
  job.bits = bits_.value_or(defaultBits(format_));
  job.compression = compression_, job.codec = codec_, job.linear = linear_;
  // 8-bit PNG renders into 8-bit targets, sRGB-encoding ones unless
  // --linear (encoded from full precision, not from 8-bit linear values);
  // everything else renders in float and is encoded as it is written.
  job.type = format_ == "png" && job.bits == 8 ? (linear_ ? PixelType::U8 : PixelType::Srgb8) : PixelType::F32;
  job.platform = parseGlPlatform(gl_);
  if (depth_ && (job.streaming() || order_ != "view" || !predistort_.empty()))
    fail("--depth", "writes a view set: not with --stream, --order epi or --predistort");
  job.depth = depth_, job.quiltOnly = quiltOnly_;
  if (!native_.empty()) {
    if (!job.quilt) fail("--native", "maps the quilt: give --quilt");
    if (job.rows > 1) fail("--native", "a lenticular panel shows one row of views: not with --rows");
    if (!isByteType(job.type)) fail("--native", "maps an 8-bit quilt: --format png with 8 bits");
    job.native = readCalibration(native_);
    job.nativeCalibration = native_;
  }
  job.predistort = predistort_;
  job.queue = queue_;
  job.memory = memory_;
  job.splitBy = splitBy_;
  job.aa = aa_;
  if (command_ != RenderCommand::Synthesize) {
    job.sequence = sequence_.resolve();
    if (job.streaming() && job.sequence.resume) fail("--resume", "keeps complete frame folders: not with a stream");
    if (job.streaming() && job.sequence.video) fail("--video", "encodes image sets' quilts: not with a stream");
    if (job.sequence.video && !job.quilt) fail("--video", "encodes the quilts: give --quilt");
  }
  return job;
}

}  // namespace mvr::app
