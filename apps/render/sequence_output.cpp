// A sequence as a job's output (issue 47): one set per frame from one
// process. The scene is read, GL started and the renderer built once; per
// frame the scene is posed in place and the renderer follows it
// (Renderer::sceneMoved: MVR redoes its lighting, transform and slicing
// only), or, for a back end that cannot, is built again.
//
// A frame's set is written into a hidden folder and renamed into place
// once its manifest is written: frame_0000/ appears complete or not at all,
// so --resume keeps exactly the frames that are there.
#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <system_error>

#include <nlohmann/json.hpp>

#include "apps/render/job_phase.h"
#include "apps/render/render_job.h"
#include "mvr/error.h"
#include "mvr/files/atomic_file.h"
#include "mvr/images/image_file.h"
#include "mvr/images/quilt_video.h"
#include "mvr/scene_pose.h"

namespace mvr::app {

namespace fs = std::filesystem;

namespace {

void replaceFolder(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove_all(to, ec);
  if (ec) fail(to.string(), "cannot replace: " + ec.message());
  fs::rename(from, to, ec);
  if (ec) fail(to.string(), "cannot move the finished frame into place: " + ec.message());
}

// A video of the sequence's quilts (or of their native images, --native),
// started with the first (which names it): the frames rendered here, and
// those an earlier run left (--resume) read back from their sets.
class VideoOut {
 public:
  enum class Of { Quilt, Native };
  VideoOut(const RenderJob& job, Of of) : job_(job), of_(of) {}
  void add(const Image& image, const std::string& name) {
    if (!video_) {
      path_ = (fs::path(job_.out) / name).string();
      video_.emplace(path_, image.width, image.height, job_.sequence.fps, job_.sequence.crf, job_.sequence.frames,
                     of_ == Of::Native ? QuiltVideo::Chroma::Full : QuiltVideo::Chroma::Half);
    }
    video_->add(image);
  }
  void addKept(const fs::path& frame) {
    const auto m = nlohmann::json::parse(std::ifstream(frame / "manifest.json"), nullptr, false);
    const nlohmann::json* file = nullptr;
    if (m.is_object() && of_ == Of::Quilt && m.contains("quilt")) file = &m["quilt"];
    if (m.is_object() && of_ == Of::Native && m.contains("native") && m["native"].is_object() &&
        m["native"].contains("image"))
      file = &m["native"]["image"];
    if (!file || !file->is_string())
      fail(frame.string(), std::string("has no ") + (of_ == Of::Quilt ? "quilt" : "native image") +
                               " to put in the video: render it again without --resume");
    const std::string name = file->get<std::string>();
    add(readImage((frame / name).string()), fs::path(name).replace_extension(".mp4").string());
  }
  void finish() {
    if (!video_) return;
    video_->finish();
    std::fprintf(stderr, "mvr: wrote %s\n", path_.c_str());
  }

 private:
  const RenderJob& job_;
  Of of_;
  std::optional<QuiltVideo> video_;
  std::string path_;
};

// Under mpirun, the video's frames reach rank 0 in order while the ranks
// render: every rank leaves the quilt (and native image) of each frame it
// renders as raw pixels in OUT/.video, and rank 0 feeds each one that is
// next in order to the encoder between its own frames, the rest once all
// ranks are done. Raw pixels, not the frames' PNGs read back: decoding a
// Portrait quilt took longer than encoding it (2 ranks on 2 cores, a
// 12-frame skinned turntable: 5.2-5.9 s, one process 2.3 s). Frames an
// earlier run left (--resume) come from their sets. The folder holds what
// rank 0 has yet to encode, and goes when rank 0 does.
class RankedVideo {
 public:
  RankedVideo(const RenderJob& job, int rank, std::optional<VideoOut>& video, std::optional<VideoOut>& native)
      : dir_(fs::path(job.out) / ".video"), rank_(rank), frames_(job.sequence.frames), video_(video),
        native_(native) {
    fs::create_directories(dir_);
    for (int k = 0; k < frames_; ++k)
      kept_.push_back(job.sequence.resume && fs::exists(fs::path(job.out) / frameFolderName(k) / "manifest.json"));
  }
  ~RankedVideo() {
    std::error_code ec;
    if (rank_ == 0) fs::remove_all(dir_, ec);
  }
  // Every rank, as each frame's image is made.
  void leave(int k, const Image& image, const std::string& name, bool native) {
    const std::string header = name + "\n" + std::to_string(image.width) + " " + std::to_string(image.height) + " " +
                               std::to_string(int(image.type)) + "\n";
    const std::string path = rawPath(k, native);
    appendToPart(path, std::as_bytes(std::span(header.data(), header.size())), true);
    finishPart(path, std::as_bytes(std::span(image.bytes.data(), image.bytes.size())));
  }
  // Rank 0: the frames that are ready, in order; with `all` (every rank
  // done) every frame left, each of which must be there.
  void feed(bool all) {
    for (; next_ < frames_; ++next_) {
      const fs::path frame = dir_.parent_path() / frameFolderName(next_);
      if (kept_[size_t(next_)]) {
        if (video_) video_->addKept(frame);
        if (native_) native_->addKept(frame);
        continue;
      }
      const bool ready = (!video_ || fs::exists(rawPath(next_, false))) && (!native_ || fs::exists(rawPath(next_, true)));
      if (!ready && !all) return;
      if (!ready) fail(frame.string(), "was rendered, but its image for the video is missing");
      if (video_) add(*video_, rawPath(next_, false));
      if (native_) add(*native_, rawPath(next_, true));
    }
  }

 private:
  std::string rawPath(int k, bool native) const {
    return (dir_ / (frameFolderName(k) + (native ? ".native" : ".quilt"))).string();
  }
  static void add(VideoOut& video, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string name;
    int w = 0, h = 0, type = 0;
    std::getline(in, name);
    in >> w >> h >> type;
    in.get();
    Image image(w, h, PixelType(type));
    in.read(reinterpret_cast<char*>(image.bytes.data()), std::streamsize(image.bytes.size()));
    if (!in || w <= 0 || h <= 0) fail(path, "is cut short");
    video.add(image, name);
    in.close();
    fs::remove(path);
  }

  fs::path dir_;
  int rank_, frames_, next_ = 0;
  std::optional<VideoOut>&video_, &native_;
  std::vector<bool> kept_;
};

nlohmann::json frameRecord(const RenderJob::Frame& f) {
  return {{"dir", frameFolderName(f.index)}, {"time_s", f.time}, {"turntable_deg", f.degrees}};
}

// sequence.json, written last: the frames and how they were made.
void writeSequenceManifest(const RenderJob& job, const PreparedJob& p, const nlohmann::json& frames) {
  const Sequence& s = job.sequence;
  nlohmann::json m = {{"frames", frames},
                      {"frame_count", s.frames},
                      {"fps", s.fps},
                      {"time_s", {s.start, s.end ? *s.end : s.timeOf(s.frames)}},
                      {"turntable", {{"degrees", s.turntable}, {"axis", "+y through the bounds centre of frame 0"}}},
                      {"scene", p.scene.source},
                      {"views", job.views},
                      {"rows", job.rows},
                      {"width", job.width},
                      {"height", job.height}};
  const std::string text = m.dump(2) + "\n";
  writeFileAtomically((fs::path(job.out) / "sequence.json").string(),
                      std::as_bytes(std::span(text.data(), text.size())));
}

// The scene at frame k: from the still, animated to t_k, turned by the
// frame's angle about the pivot.
void pose(const RenderJob& job, PreparedJob& p, const RenderJob::Frame& frame, const glm::vec3& pivot) {
  poseJob(job, p, frame.time, turntable(pivot, frame.degrees));
}

// The scene and the renderer at each frame in turn: posed from the still
// when the frame differs from the one they show; a back end that cannot
// follow the scene (Renderer::sceneMoved) is built again.
class FrameMover {
 public:
  FrameMover(const RenderJob& job, PreparedJob& p) : job_(job), p_(p), pivot_(p.scene.bounds().center()) {}
  void moveTo(const RenderJob::Frame& frame) {
    const Sequence& s = job_.sequence;
    const bool animated = !p_.scene.animations.empty();
    if (frame.index == posed_ || (!animated && frame.degrees == s.degreesAt(posed_))) return;
    pose(job_, p_, frame, pivot_);
    posed_ = frame.index;
  }

 private:
  const RenderJob& job_;
  PreparedJob& p_;
  glm::vec3 pivot_;  // frame 0's bounds' centre
  int posed_ = 0;    // the renderer's scene is frame 0's
};

// Frames counted as they are done, with the time left: this process's
// frames, one in `ranks` of the sequence's when ranks share it (rank 0
// reports).
class FrameProgress {
 public:
  FrameProgress(int frames, int ranks, bool reports) : frames_(frames), ranks_(ranks), reports_(reports) {}
  void done(const RenderJob::Frame& frame) {
    ++rendered_;
    if (!reports_) return;
    const double each = total_.seconds() / rendered_;
    const int left = (frames_ - frame.index - 1 + ranks_ - 1) / ranks_;
    std::fprintf(stderr, "mvr: frame %d of %d (t %.3f s, %.1f deg) done, %.3f s a frame, about %.0f s left\n",
                 frame.index + 1, frames_, frame.time, frame.degrees, each, each * left);
  }
  int rendered() const { return rendered_; }
  double seconds() const { return total_.seconds(); }

 private:
  int frames_, ranks_, rendered_ = 0;
  bool reports_;
  Stopwatch total_;
};

RenderJob::Frame frameAt(const Sequence& s, int k) { return {k, s.timeOf(k), s.degreesAt(k)}; }

// Every frame allocates the same large buffers (the quilt, the reorder
// volume, the EPIs) and frees them: kept in the heap instead of given back
// to the system, the next frame reuses their pages. Given back, each frame
// faulted them in afresh (0.16 of 0.51 s a frame of a Portrait quilt on 2
// cores, in the kernel).
void keepLargeBuffers() {
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

// The frames one after another into one stream, its header saying how
// many (docs/EPI_STREAM.md).
int streamSequence(const RenderJob& job, PreparedJob& p) {
  const Sequence& s = job.sequence;
  keepLargeBuffers();
  FrameMover mover(job, p);
  FrameProgress progress(s.frames, 1, true);
  StreamedFrames frames{.count = s.frames, .startTime = s.start, .frameRate = s.fps,
                        .beforeFrame = [&](int k) { mover.moveTo(frameAt(s, k)); },
                        .afterFrame = [&](int k) { progress.done(frameAt(s, k)); }};
  return writeStream(job, p, frames);
}

}  // namespace

void startSequence(RenderJob& job, PreparedJob& p) {
  if (p.mpi) fail("--frames", "a streamed sequence is not split across ranks: stream it from one process");
  Sequence& s = job.sequence;
  if (!s.clip.empty() && !hasClip(p.scene, s.clip))
    fail("--clip", "the scene has no animation clip named '" + s.clip + "'");
  s.fromAnimation(animationLength(p.scene, s.clip));
  p.still = std::make_shared<const Scene>(p.scene);
  if (p.scene.animations.empty()) return;
  frameEveryPose(job, p);
  pose(job, p, frameAt(s, 0), glm::vec3(0.0f));  // the pose set-up starts from
}

int writeSequence(const RenderJob& job, PreparedJob& p) {
  if (job.streaming()) return streamSequence(job, p);
  const Sequence& s = job.sequence;
  // Under mpirun the ranks share the frames, interleaved (neighbouring
  // frames cost alike, so each rank's share costs alike), each frame a
  // whole set as one process writes it; the video is encoded once, by
  // rank 0, from the finished frames in order (RankedVideo).
  MpiSession* const share = p.frameShare;
  const int ranks = share ? share->ranks() : 1, rank = share ? share->rank() : 0;
  keepLargeBuffers();
  FrameMover mover(job, p);
  FrameProgress progress(s.frames, ranks, rank == 0);
  const StageTimes startup = p.startup;  // the process's, in every frame's manifest
  fs::create_directories(job.out);
  std::optional<VideoOut> video, nativeVideo;
  if (s.video) video.emplace(job, VideoOut::Of::Quilt);
  if (s.video && job.native) nativeVideo.emplace(job, VideoOut::Of::Native);
  std::optional<RankedVideo> ranked;
  if (s.video && share) ranked.emplace(job, rank, video, nativeVideo);
  int current = 0;  // the frame being rendered, for the ranked video
  if (ranked) {
    p.quiltOut = [&](const Image& quilt, const std::string& name) { ranked->leave(current, quilt, name, false); };
    if (nativeVideo)
      p.nativeOut = [&](const Image& native, const std::string& name) { ranked->leave(current, native, name, true); };
  } else if (video) {
    p.quiltOut = [&](const Image& quilt, const std::string& name) { video->add(quilt, name); };
    if (nativeVideo)
      p.nativeOut = [&](const Image& native, const std::string& name) { nativeVideo->add(native, name); };
  }
  inPhase(share, [&] {
    for (int k = rank; k < s.frames; k += ranks) {
      const RenderJob::Frame frame = frameAt(s, k);
      const fs::path final = fs::path(job.out) / frameFolderName(k);
      if (ranked && rank == 0) ranked->feed(false);
      if (s.resume && fs::exists(final / "manifest.json")) {
        if (!share) {
          if (video) video->addKept(final);
          if (nativeVideo) nativeVideo->addKept(final);
        }
        continue;
      }
      current = k;
      const Stopwatch posing;
      mover.moveTo(frame);
      p.poseSeconds = posing.seconds();
      RenderJob one = job;
      one.frame = frame;
      p.startup = startup;
      const fs::path partial = fs::path(job.out) / ("." + frameFolderName(k) + ".partial");
      std::error_code ec;
      fs::remove_all(partial, ec);
      one.out = partial.string();
      if (writeSet(one, p) != 0) fail(final.string(), "the frame's set was not written");
      replaceFolder(partial, final);
      progress.done(frame);
    }
  });
  p.quiltOut = nullptr, p.nativeOut = nullptr;
  int rendered = progress.rendered();
  if (share) {
    rendered = 0;
    for (const std::string& n : share->gatherAtRoot({std::to_string(progress.rendered())})) rendered += std::stoi(n);
    if (rank != 0) return 0;
    if (ranked) ranked->feed(true);
  }
  if (video) video->finish();
  if (nativeVideo) nativeVideo->finish();
  nlohmann::json frames = nlohmann::json::array();
  for (int k = 0; k < s.frames; ++k) frames.push_back(frameRecord(frameAt(s, k)));
  writeSequenceManifest(job, p, frames);
  std::fprintf(stderr, "mvr: rendered %d of %d frames (%d views each) to %s in %.3f s%s\n", rendered, s.frames,
               job.views * job.rows, job.out.c_str(), progress.seconds(),
               share ? (", " + std::to_string(ranks) + " ranks").c_str() : "");
  return 0;
}

}  // namespace mvr::app
