// An image set as a job's output: views or EPIs, a quilt, depth maps and
// the manifest, from one process or from every rank of a split job.
#include <cstdio>
#include <memory>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "apps/render/depth_pass.h"
#include "apps/render/job_phase.h"
#include "apps/render/render_job.h"
#include "apps/render/split_output.h"
#include "mvr/error.h"
#include "mvr/images/image_codec.h"
#include "mvr/images/image_set.h"

namespace mvr::app {

namespace {

// What the set's frames passed through, and how long each part took.
struct SetRun {
  RenderStats stats, depthStats;
  double renderSeconds = 0.0, colorSeconds = 0.0;
  Stopwatch total;
  std::unique_ptr<QuiltSink> quilt;
  double quiltAspect = 0.0;
  std::optional<SplitOutput> split;
  nlohmann::json reorder;
  std::string scratchNote;
};

std::unique_ptr<QuiltSink> makeQuilt(const RenderJob& job) {
  if (job.order != "view") fail("--quilt", "needs --order view");
  auto quilt = std::make_unique<QuiltSink>(job.width, job.height, job.views, job.rows, job.type, job.quilt->columns,
                                           job.quilt->rows);
  if (const long tiles = long(quilt->columns()) * quilt->tileRows(); tiles > long(job.views) * job.rows)
    std::fprintf(stderr, "mvr: warning: the %dx%d quilt leaves %ld of its tiles empty\n", quilt->columns(),
                 quilt->tileRows(), tiles - long(job.views) * job.rows);
  return quilt;
}

// native_{W}x{H}.png, .mp4: the panel's native image and its video.
std::string nativeName(const RenderJob& job, const std::string& extension) {
  return "native_" + std::to_string(job.native->screenW) + "x" + std::to_string(job.native->screenH) + "." + extension;
}

// The manifest's record of the job beyond the set's layout.
void describe(const RenderJob& job, const PreparedJob& p, const SetRun& run, Manifest& manifest) {
  nlohmann::json& m = manifest.info;
  if (job.synthesize()) {
    m["references"] = {{"from", job.from}, {"layout", job.references->layout}, {"count", p.referenceCount},
                       {"tau", job.warp.tau}, {"penalty", job.warp.penalty}};
  } else {
    m["scene"] = p.scene.source;
    m["triangles"] = p.scene.triangleCount();
  }
  m["backend"] = p.renderer->name();
  if (job.backend.hasPst()) m["pst"] = pstModeName(job.backend.pst());
  m["gl"] = {{"platform", glPlatformName(p.context->platform())},
             {"version", p.context->version()},
             {"renderer", p.context->renderer()}};
  // V already holds the focal plane's move.
  const glm::dmat4 plane = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, p.imagePlaneZ));
  manifest.setCamera(*p.camera, p.imagePlaneZ, plane * glm::dmat4(p.scene.fromFile));
  if (job.aa.active())
    m["antialiasing"] = {{"filter", "box, in linear light, colour weighted by alpha"},
                         {"samples_per_pixel", job.aa.spatial * job.aa.spatial},
                         {"samples_per_view", job.aa.views},
                         {"depth", "not filtered: depth maps sample pixel centres"}};
  if (const std::optional<glm::vec4> b = job.camera.backgroundColor()) m["background"] = {b->r, b->g, b->b, b->a};
  m["timings_s"] = run.stats.times.seconds;
  m["timings_s"]["total"] = run.total.seconds();
  if (p.poseSeconds > 0.0) m["timings_s"]["pose"] = p.poseSeconds;
  StageTimes startup = p.startup;
  if (const double load = imageCodecLoadSeconds(); load > 0.0) startup.add("image_module_load", load);
  m["startup_s"] = startup.seconds;
  m["counters"] = run.stats.counters;
  m["notes"] = run.stats.notes;
  m["pixel_origin"] = "top-left; view i at camera x = track[0] + i * view_spacing";
  if (job.frame)
    m["frame"] = {{"index", job.frame->index}, {"time_s", job.frame->time}, {"turntable_deg", job.frame->degrees}};
  if (run.quilt) {
    m["quilt"] = run.quilt->fileName(job.format, run.quiltAspect);
    m["quilt_layout"] = {{"columns", run.quilt->columns()},
                         {"rows", run.quilt->tileRows()},
                         {"aspect", run.quiltAspect},
                         {"order", job.rows > 1 ? "grid row 0 at the top, views left to right"
                                                : "view 0 at the bottom left, left to right, then upwards"}};
    if (!job.quilt->preset.empty()) m["quilt_layout"]["preset"] = job.quilt->preset;
  }
  if (run.quilt && job.native)
    m["native"] = {{"image", nativeName(job, "png")}, {"calibration", job.nativeCalibration},
                   {"mapping", "docs/DISPLAY.md: each subpixel from the view its lens sends that way"}};
  if (!run.reorder.is_null()) m["reorder"] = run.reorder;
  if (!job.predistort.empty()) m["predistortion"] = job.predistort;
  if (job.depth) {
    m["timings_s"]["color"] = run.colorSeconds;
    m["depth"] = {{"files", manifest.depthPattern() + ".exr"},
                  {"channel", "Z"},
                  {"measure", "distance along the view axis (camera z of V in cameras), world units"},
                  {"background", 0},
                  {"timings_s", run.depthStats.times.seconds}};
  }
}

// The panel's native image of the finished quilt, by the GL pass (built
// once, with the first quilt).
Image nativeOf(const RenderJob& job, PreparedJob& p, const QuiltSink& quilt) {
  const Image& q = quilt.quilt();
  const LenticularMap map =
      LenticularMap::of(*job.native, {quilt.columns(), quilt.tileRows(), job.views, job.width, job.height}, q.height);
  if (!p.panel) p.panel = std::make_unique<LenticularPass>(map);
  return p.panel->render(q);
}

// The colour pass: the chain from the renderer to the writer (and quilt),
// rendered; a split job's frames exchanged and assembled.
void renderColor(const RenderJob& job, PreparedJob& p, ImageSetWriter& writer, SetRun& run) {
  MpiSession* const mpi = p.mpi;
  FrameChainSpec spec = p.chainSpec(job);
  if (!job.predistort.empty()) spec.predistortion = loadPredistortionTable(job.predistort, job.width);
  if (job.quilt && (!mpi || mpi->rank() == 0)) run.quilt = makeQuilt(job);
  FrameDestination destination{.sink = &writer, .set = &writer, .quilt = run.quilt.get(), .frames = !job.quiltOnly};
  if (mpi) {
    // Set-up is done on every rank once they agree; then each renders its share.
    const JobSplit split = splitFor(job, p);
    // The shared files: the colour's and the depth's, which lives after it.
    const bool exchanges = p.reorders && split.gridBegin() < job.rows;
    const size_t shared = (job.quilt || exchanges ? p.rowBytes * job.rows : 0) +
                          (p.depthReorders && split.gridBegin() < job.rows ? p.depthRowBytes * job.rows : 0);
    if (shared > 0) checkScratchFits(shared, job.out);
    if (!mpi->agree("")) throw JobFailed{};
    run.split.emplace(*mpi, *p.camera, split,
                      SplitOutputSpec{.rendered = p.renderer->order(), .toViews = job.order == "view",
                                      .type = job.type, .dir = job.out, .quilt = job.quilt.has_value(),
                                      .frames = !job.quiltOnly, .reorder = p.reorder},
                      writer, run.quilt.get());
    destination = {.sink = &run.split->sink()};  // it reorders and exchanges
  } else {
    spec.delivered = job.order == "view" ? FrameOrder::View : FrameOrder::Epi;
    spec.pngRows = p.pngRows;
  }
  FrameChain chain(destination, spec);
  p.startup.add("before_render", p.sinceStart.seconds());
  run.total.restart();
  // This process's, before waiting for the others.
  run.renderSeconds = renderPhase(mpi, *p.renderer, rendersOf(*p.renderCamera, run.split ? &*run.split : nullptr, job.aa),
                                  chain.entry(), long(job.views) * job.rows, p.label(job.backend), run.stats);
  run.quiltAspect = job.quilt && job.quilt->aspect > 0.0 ? job.quilt->aspect : double(job.width) / job.height;
  inPhase(mpi, [&] {
    if (run.split) run.split->assemble();
    if (run.quilt) {
      // The quilt's and native image's users first: then the writer takes them.
      if (p.quiltOut) p.quiltOut(run.quilt->quilt(), run.quilt->fileName("mp4", run.quiltAspect));
      if (job.native) {
        Image native = nativeOf(job, p, *run.quilt);
        if (p.nativeOut) p.nativeOut(native, nativeName(job, "mp4"));
        writer.putExtra(nativeName(job, "png"), std::move(native), {});
      }
      writer.putExtra(run.quilt->fileName(job.format, run.quiltAspect), run.quilt->takeQuilt(),
                      {{"Exif:UserComment", quiltMetadata(job.views * job.rows, run.quilt->columns(),
                                                          run.quilt->tileRows(), run.quiltAspect)}});
    }
    if (mpi) writer.flush();
  });
  run.reorder = chain.reorderInfo();
  run.scratchNote = chain.scratchNote();
}

}  // namespace

int writeSet(const RenderJob& job, PreparedJob& p) {
  MpiSession* const mpi = p.mpi;
  ImageSetWriter writer(job.out, job.manifest());
  if (p.scratch) checkScratchFits(p.rowBytes, p.reorder.scratchDir);  // the output folder exists now
  if (p.depthReorders && p.depthReorder.spills(p.depthRowBytes))
    checkScratchFits(p.depthRowBytes, p.depthReorder.scratchDir);
  SetRun run;
  renderColor(job, p, writer, run);
  run.colorSeconds = run.total.seconds();
  if (job.depth)
    renderDepth(job.backend, p.scene, *p.camera, writer, p.depthReorder, run.depthStats, mpi,
                run.split ? &run.split->split() : nullptr, job.out);
  writer.flush();  // every image encoded, so the module's load is done and timed
  Manifest& manifest = writer.manifest();
  describe(job, p, run, manifest);
  if (run.split) {
    manifest.info["mpi"] = run.split->info();
    manifest.info["mpi"]["split_by"] = job.splitBy;
    std::vector<double> seconds;  // every rank's rendering, in rank order
    for (const std::string& t : mpi->gatherAtRoot({std::to_string(run.renderSeconds)})) seconds.push_back(std::stod(t));
    manifest.info["mpi"]["render_s"] = seconds;
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
  const int views = job.views * job.rows;
  if (job.frame) return 0;  // the sequence reports its frames
  std::fprintf(stderr, "mvr: rendered %d view%s of %dx%d with %s to %s in %.3f s%s\n", views, views == 1 ? "" : "s",
               job.width, job.height, p.label(job.backend).c_str(), job.out.c_str(), run.total.seconds(),
               run.scratchNote.c_str());
  return 0;
}

}  // namespace mvr::app
