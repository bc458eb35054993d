#pragma once
// A render, stream or synthesis as a job: described once the command line
// is read (render_flags.h), then run in three steps: set-up (the scene and
// GL side by side, the camera, the renderer), the memory plan (what is held
// for reordering, decided before anything renders), and the output: an
// image set (set_output.cpp) or the EPI-major stream (stream_output.cpp).
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "apps/cli/backend_flags.h"
#include "apps/cli/cli.h"
#include "apps/cli/camera_flags.h"
#include "apps/cli/job_split.h"
#include "apps/cli/memory_check.h"
#include "apps/cli/quilt_layout.h"
#include "apps/cli/sequence_flags.h"
#include "mvr/backends/warp/warp_renderer.h"
#include "mvr/frames/frame_chain.h"
#include "mvr/gl/gl_context.h"
#include "mvr/gl/lenticular_pass.h"
#include "mvr/images/image_file.h"
#include "mvr/images/manifest.h"
#include "mvr/images/rgbd_set.h"
#include "mvr/scene.h"
#include "mvr/tone_map.h"
#include "mvr/timer.h"

namespace mvr::app {

// Which command a job is (apps/render/render_command.h).
enum class RenderCommand { Render, Stream, Synthesize };

class MpiSession;

// Every choice of the command line, resolved and checked.
struct RenderJob {
  RenderCommand command = RenderCommand::Render;
  BackendFlags backendFlags;  // the default accuracy mode needs GL and the scene
  BackendOptions backend;
  std::string scenePath;
  bool strict = false;
  LookOptions look;  // --exposure, --environment
  ToneMap toneMap = ToneMap::None;  // --tonemap
  std::optional<RgbdSet> references;  // synthesize
  std::string from;
  WarpOptions warp;
  int views = 16, rows = 1, width = 320, height = 240;
  std::string out, format, order;
  int bits = 8, compression = kDefaultPngCompression;
  std::string codec;
  bool linear = false;
  PixelType type = PixelType::Srgb8;
  GlPlatform platform = GlPlatform::Egl;
  bool currentGl = false;  // render in the calling thread's current GL context (mvr live's screen); none is made
  bool depth = false, quiltOnly = false;
  std::optional<QuiltLayout> quilt;
  std::optional<PanelCalibration> native;  // --native: the panel the quilt is mapped to
  std::string nativeCalibration;           // its file
  std::string predistort;
  std::string stream;  // the stream's endpoint; empty: an image set
  int queue = 8;
  MemoryFlags memory;
  std::string splitBy;
  CameraFlags camera;
  Supersampling aa;
  Sequence sequence;  // frames: a sequence of sets (sequence_output.cpp)
  // One frame of a sequence, as its set's manifest records it.
  struct Frame {
    int index = 0;
    double time = 0.0, degrees = 0.0;
  };
  std::optional<Frame> frame;

  bool streaming() const { return !stream.empty(); }
  bool synthesize() const { return command == RenderCommand::Synthesize; }
  // The set's layout and encoding, as its manifest records them.
  Manifest manifest() const;
};

// What set-up made, and the memory plan.
struct PreparedJob {
  Scene scene;
  std::unique_ptr<GlContext> context;
  double imagePlaneZ = 0.0;
  std::optional<ShearingCamera> camera, renderCamera;  // the set's, and the one rendered (samples)
  std::unique_ptr<Renderer> renderer;
  size_t referenceCount = 0;
  StageTimes startup;
  Stopwatch sinceStart;
  double poseSeconds = 0.0;  // a sequence's frame: posing its scene (skins, morphs, nodes)
  MpiSession* mpi = nullptr;  // a set split over ranks
  // A sequence under mpirun: the ranks share its frames, each frame a
  // whole set written as one process writes it (mpi stays null).
  MpiSession* frameShare = nullptr;
  // Frames held, decided before rendering starts.
  bool reorders = false, depthReorders = false;
  ReorderMemory reorder, depthReorder;
  std::optional<PngRows> pngRows;  // EPIs straight into PNG views
  // A sequence: the scene as it was read, moved as set-up moved p.scene
  // (into a file's camera, behind the focal plane); p.scene is posed from
  // it (poseJob).
  std::shared_ptr<const Scene> still;
  // An animated scene: the bounds of its every pose, which the camera frames
  // (frameEveryPose).
  std::optional<Bounds> framed;
  // A sequence's video: each frame's finished quilt, with its file name.
  std::function<void(const Image& quilt, const std::string& name)> quiltOut;
  // ... and its native image (--native), with the file name of its video.
  std::function<void(const Image& native, const std::string& name)> nativeOut;
  std::unique_ptr<LenticularPass> panel;  // --native's GL pass, built with the first quilt
  bool scratch = false;            // the colour's reorder spills to a scratch file
  size_t rowBytes = 0, depthRowBytes = 0;

  // "mvr cpu": the renderer and its accuracy mode, for summaries and progress.
  std::string label(const BackendOptions& backend) const;
  // The chain's frames in the renderer's order, with the job's
  // supersampling and background; callers add the rest.
  FrameChainSpec chainSpec(const RenderJob& job) const;
};

// How a split job's ranks share it: the same on every rank (apps/cli/job_split.h).
JobSplit splitFor(const RenderJob& job, const PreparedJob& prepared);

int runJob(RenderJob& job);
// What runJob does before it renders: GL started on this thread, the
// scene read, the camera framed, the renderer built, the memory planned.
void prepareJob(RenderJob& job, PreparedJob& prepared);
// The job's back end for a scene: rendering the job's pixel type, or with
// --tonemap in float, tone mapped into it.
std::unique_ptr<Renderer> makeSceneRenderer(const RenderJob& job, const Scene& scene);
// The scene posed from prepared.still: its animations at `time` (the
// job's clip), then moved by `move` in world space; the renderer follows
// it (Renderer::sceneMoved) or, a back end that cannot, is built again
// (none yet: a sequence's frame 0 is posed before the renderer is built).
void poseJob(const RenderJob& job, PreparedJob& prepared, double time, const glm::mat4& move);
// A scene that plays an animation is framed on every pose of the clips
// that play (framingTimes: their key times, not the frames'), so that a
// character that walks stays in the picture and frame k of a sequence is
// the still render at its time (--frames 1 --time t_k), whatever the
// sequence's range. Sets prepared.framed; the scene is left as the still.
// A turntable's turns are not framed (its framing is the unturned scene's).
void frameEveryPose(const RenderJob& job, PreparedJob& prepared);
int writeSet(const RenderJob& job, PreparedJob& prepared);
// The frames of one stream: a still's one, or a sequence's, each posed
// by beforeFrame(k) before it is rendered; afterFrame(k) once it is.
struct StreamedFrames {
  int count = 1;
  double startTime = 0.0, frameRate = 0.0;
  std::function<void(int)> beforeFrame, afterFrame;
};
int writeStream(const RenderJob& job, PreparedJob& prepared, const StreamedFrames& frames = {});
// A sequence's frame count (an animation's length) and its frame 0, posed
// before the camera is framed on it.
void startSequence(RenderJob& job, PreparedJob& prepared);
int writeSequence(const RenderJob& job, PreparedJob& prepared);

}  // namespace mvr::app
