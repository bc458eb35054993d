#include "apps/render/render_job.h"

#include <glm/gtc/matrix_transform.hpp>

#include <future>
#include <utility>

#include "apps/cli/cli.h"
#include "apps/cli/job_split.h"
#include "apps/render/mpi_session.h"
#include "mvr/error.h"
#include "mvr/frames/progress.h"
#include "mvr/frames/tone_mapped_renderer.h"
#include "mvr/images/image_codec.h"
#include "mvr/assets/scene_io.h"
#include "mvr/parallel.h"
#include "mvr/scene_pose.h"
#include "shading/shading_plan.h"

namespace mvr::app {

Manifest RenderJob::manifest() const {
  return Manifest{.views = views, .rows = rows, .width = width, .height = height, .format = format,
                  .order = order, .bits = bits, .compression = compression, .codec = codec, .srgb = !linear};
}

std::string PreparedJob::label(const BackendOptions& backend) const {
  return renderer->name() + (backend.hasPst() ? std::string(" ") + pstModeName(backend.pst()) : "");
}

namespace {

// The pool, the image module, the scene and GL; startup times as they go.
void start(RenderJob& job, PreparedJob& p) {
  // Under mpirun the ranks share the job (apps/cli/job_split.h); rank 0 reports.
  p.mpi = MpiSession::current();
  if (p.mpi && job.sequence.active() && !job.streaming()) p.frameShare = std::exchange(p.mpi, nullptr);
  if (MpiSession::current() && MpiSession::current()->rank() != 0) setProgressEnabled(false);
  // OpenImageIO (about 260 libraries) loads beside the scene's loading,
  // for the files PNG is not (mvr/images/png_encoder.h writes PNGs). Not later:
  // dlopen holds the dynamic loader's lock, which GL start-up (its driver),
  // the pool's start-up and llvmpipe's shader compiler (its symbol
  // lookups) all take, so whatever runs beside the load waits for it
  // unless it is pure computation like reading the scene. Started after
  // GL, a one-view render took 0.78-0.82 s against 0.69-0.70 s.
  startPool();
  // Depth maps of the default codec are our own encoder's (mvr/images/exr_depth.h).
  if (!job.streaming() && (job.format != "png" || (job.depth && !ownsDepthCodec(job.codec)))) preloadImageCodec();
  // Where start-up time goes, in the manifest (issue 15).
  p.sinceStart.restart();
  // The scene loads on a worker while GL starts here (a context belongs to
  // the thread that made it): 143K triangles take 0.13 s, GL 0.08 s.
  auto loading = std::async(std::launch::async, [&] {
    const Stopwatch watch;
    Scene loaded = job.synthesize() ? Scene{} : loadInputScene(job.scenePath, job.strict, job.look);
    loaded.highDynamicRange = job.toneMap != ToneMap::None;
    return std::pair{std::move(loaded), watch.seconds()};
  });
  try {
    if (!job.currentGl) p.context = GlContext::create(job.platform);
  } catch (...) {
    (void)loading.get();  // input problems first: the scene's error, if it has one
    throw;
  }
  p.startup.add("gl", p.sinceStart.seconds());
  double sceneSeconds = 0.0;
  std::tie(p.scene, sceneSeconds) = loading.get();
  if (!job.synthesize()) job.backendFlags.chooseDefaultPst(job.backend, p.scene);
  p.startup.add("scene", sceneSeconds);
}

// A move set-up gives the scene (into a file's camera, behind the focal
// plane), given to the still a sequence poses it from as well.
void moveStill(PreparedJob& p, const glm::mat4& m) {
  if (!p.still) return;
  auto moved = std::make_shared<Scene>(*p.still);
  moved->transform(m);
  p.still = std::move(moved);
}

// The set's camera, the one rendered, and the renderer.
void setUp(RenderJob& job, PreparedJob& p) {
  Stopwatch phase;
  if (const shading::ShadingPlan plan = shading::planShading(p.scene); plan.texture || plan.reflection)
    preloadImageCodec();  // a stream of a textured scene reads images too
  const bool synthesize = job.synthesize();
  if (synthesize && !job.camera.fileCamera.empty()) fail("--camera", "needs a scene (synthesize takes the references' camera)");
  // The scene's moves into the rig, given to the still it is posed from too.
  if (const glm::mat4 m = job.camera.viewThroughFileCamera(p.scene, job.width, job.height); m != glm::mat4(1.0f)) {
    moveStill(p, m);
    p.framed.reset();  // the file's camera frames the scene
  }
  p.imagePlaneZ = job.camera.placeFocalPlane(p.scene, p.framed ? &*p.framed : nullptr);
  if (p.imagePlaneZ != 0.0) {
    moveStill(p, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -float(p.imagePlaneZ))));
    if (p.framed) p.framed->min.z -= float(p.imagePlaneZ), p.framed->max.z -= float(p.imagePlaneZ);
  }
  CameraSpec spec = synthesize    ? job.references->camera
                    : p.framed && !p.scene.camera ? ShearingCamera::frame(*p.framed, job.width, job.height)
                                                  : cameraFor(p.scene, job.width, job.height);
  if (synthesize && (job.width != job.references->width || job.height != job.references->height))
    spec.planeHeight = 0.0;  // another size: the image plane's height from its aspect
  spec = job.camera.adjust(spec, job.width, job.height);
  // The display stretches the tiles to its aspect: the plane has it.
  if (job.quilt && job.quilt->aspect > 0.0) spec.planeHeight = spec.planeWidth / job.quilt->aspect;
  const ShearingCamera& camera = p.camera.emplace(spec, job.width, job.height, job.views, job.rows);
  if (job.aa.views > 1 && job.views < 2) fail("--aa-views", "needs at least 2 views: one view has no track to sample");
  // Anti-aliasing: the back end renders the samples, a sink filters them.
  p.renderCamera.emplace(job.aa.active() ? supersampledCamera(camera, job.aa) : camera);
  p.referenceCount = synthesize ? job.references->references.size() : 0;
  p.renderer = synthesize ? makeWarpRenderer(std::move(job.references->references), job.type, job.warp, &*p.renderCamera)
                          : makeSceneRenderer(job, p.scene);
  p.startup.add("renderer", phase.restart());
}

// Frames held, decided before rendering starts: a reordering sink's row
// within the memory budget (beyond it, a scratch file), a quilt whole.
void planMemory(const RenderJob& job, PreparedJob& p) {
  const bool streaming = job.streaming();
  const FrameOrder rendered = p.renderer->order();
  const size_t pixelBytes = 4 * Image::channelBytes(job.type);
  const size_t viewBytes = size_t(job.width) * job.height * pixelBytes;
  p.rowBytes = viewBytes * job.views;
  p.reorders = streaming ? rendered == FrameOrder::View : (rendered == FrameOrder::Epi) == (job.order == "view");
  if (p.reorders) {
    // The frames the sink hands on, and how many its consumer holds in flight.
    const bool toViews = !streaming && job.order == "view";
    p.reorder = job.memory.reorder(toViews ? viewBytes : size_t(job.width) * job.views * pixelBytes,
                                   streaming ? job.queue : BoundedTasks::defaultLimit(), streaming ? "." : job.out);
  }
  // 8-bit PNG views from EPIs take each EPI's rows into their encoders and
  // hold the files' bytes (within the budget, beyond it on their way to
  // disk), no volume: what is left to reorder through a scratch file is
  // the rest. A queue lets a GL renderer draw while the pool encodes; the
  // CPU span back end renders on that pool.
  if (p.reorders && !streaming && !p.mpi && job.order == "view" && !job.quilt)
    p.pngRows = planPngRows(job.manifest(), job.type, p.reorder.budget,
                            job.backend.hasPst() && job.backend.pst() == PstMode::Cpu);
  p.scratch = p.reorders && !p.pngRows && p.reorder.spills(p.rowBytes);
  // The depth pass reorders its packed frames (mvr/depth.h) where the back end renders EPIs.
  const size_t depthViewBytes = size_t(job.width) * job.height * 4 * Image::channelBytes(kPackedDepth);
  p.depthRowBytes = depthViewBytes * job.views;
  p.depthReorders = job.depth && rendered == FrameOrder::Epi;
  if (p.depthReorders) p.depthReorder = job.memory.reorder(depthViewBytes, BoundedTasks::defaultLimit(), job.out);
  const bool quilt = !streaming && job.quilt && (!p.mpi || p.mpi->rank() == 0);
  checkHeldFramesFit({.reorderBytes = std::max(p.reorders ? p.reorder.held(p.rowBytes) : 0,
                                               p.depthReorders ? p.depthReorder.held(p.depthRowBytes) : 0),
                      .quiltBytes = quilt ? p.rowBytes * job.rows : 0},
                     availableMemory(),
                     std::string("give a smaller --memory") + (job.quilt ? ", drop --quilt" : "") +
                         ", fewer views or a smaller size");
  if (p.scratch && streaming) checkScratchFits(p.rowBytes, p.reorder.scratchDir);
}

}  // namespace

JobSplit splitFor(const RenderJob& job, const PreparedJob& p) {
  return splitJob(*p.camera, p.renderer->order(), p.mpi->ranks(),
                  job.synthesize() || job.splitBy == "count" ? std::vector<double>{}
                                                             : scanlineCosts(p.scene, *p.camera, job.rows / 2));
}

FrameChainSpec PreparedJob::chainSpec(const RenderJob& job) const {
  return FrameChainSpec{.rendered = renderer->order(), .delivered = renderer->order(), .width = job.width,
                        .height = job.height, .views = job.views, .type = job.type, .reorder = reorder,
                        .aa = job.aa, .background = job.camera.backgroundColor()};
}

void prepareJob(RenderJob& job, PreparedJob& prepared) {
  start(job, prepared);
  prepared.still = std::make_shared<const Scene>(prepared.scene);  // live poses the scene
  frameEveryPose(job, prepared);
  setUp(job, prepared);
  planMemory(job, prepared);
}

std::unique_ptr<Renderer> makeSceneRenderer(const RenderJob& job, const Scene& scene) {
  if (job.toneMap == ToneMap::None) return makeRenderer(job.backend, scene, job.type);
  // Shaded in float, tone mapped into the output's type (mvr/tone_map.h).
  return std::make_unique<ToneMappedRenderer>(makeRenderer(job.backend, scene, PixelType::F32), job.toneMap, job.type);
}

void poseJob(const RenderJob& job, PreparedJob& p, double time, const glm::mat4& move) {
  poseGeometry(p.scene, *p.still, move);
  poseAnimations(p.scene, time, job.sequence.clip, move);
  if (p.renderer && !p.renderer->sceneMoved()) p.renderer = makeSceneRenderer(job, p.scene);
}

void frameEveryPose(const RenderJob& job, PreparedJob& p) {
  // A 100K-vertex skin poses in about 3 ms: a clip of any length adds at
  // most 0.4 s to the set-up.
  constexpr size_t kMostPoses = 128;
  const std::vector<double> times = framingTimes(p.scene, job.sequence.clip, kMostPoses);
  if (times.empty()) return;
  Bounds all = Bounds::none();
  for (double t : times) {
    poseJob(job, p, t, glm::mat4(1.0f));
    const Bounds b = p.scene.bounds();
    all.include(b.min), all.include(b.max);
  }
  p.framed = all;
  poseGeometry(p.scene, *p.still, glm::mat4(1.0f));  // the still, as it was loaded
}

int runJob(RenderJob& job) {
  PreparedJob prepared;
  start(job, prepared);
  if (job.sequence.active()) startSequence(job, prepared);
  setUp(job, prepared);
  planMemory(job, prepared);
  if (job.sequence.active()) return writeSequence(job, prepared);
  return job.streaming() ? writeStream(job, prepared) : writeSet(job, prepared);
}

}  // namespace mvr::app
