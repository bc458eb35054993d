#pragma once
// mvr live's renderer (issue 48): the scene's views, one set after
// another, in one of two places.
// - On a thread of its own with its own GL context (EGL), so that
//   rendering frame k + 1 overlaps showing frame k: the CPU path, where
//   the CPU renders and the GL (llvmpipe) maps. Each set is an EPI volume
//   in host memory (mvr/lenticular.h), where an EPI renderer writes in
//   place and the panel mapping finds a panel row's views close together;
//   two alternate, the one shown stays whole while the next is drawn, and
//   the screen uploads it.
// - In the screen's own context, into its texture (a FrameSink over it:
//   mvr/gl/view_layers.h): the GPU path, where the GPU spans write each
//   EPI into the texture's layers, or a view renderer copies each view
//   into its layer, and nothing is read back. The GPU queues the frames;
//   the CPU's part is a frame's commands.
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <glm/glm.hpp>

#include "apps/render/render_job.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/lenticular.h"

namespace mvr::app {

// What one live frame shows: the scene's animation at `time`, then moved
// by `move` (the viewer's orbit, zoom and focal plane) in world space.
struct LivePose {
  double time = 0.0;
  glm::mat4 move{1.0f};
};

// The quilt a live job renders: its grid of tiles and their size.
QuiltGrid liveGrid(const RenderJob& job);

class LiveQuilts {
 public:
  // Prepares the job (GL, scene, camera, renderer); its errors are thrown
  // here. Not onScreen: on the render thread, in a context of its own.
  // onScreen: on this thread, in its current context, rendering into the
  // screen attach() gives.
  LiveQuilts(RenderJob job, bool onScreen);
  ~LiveQuilts();
  LiveQuilts(const LiveQuilts&) = delete;
  LiveQuilts& operator=(const LiveQuilts&) = delete;

  const RenderJob& job() const { return job_; }
  // The renderer's order: the layout a screen it renders into takes.
  FrameOrder order() const { return order_; }
  // onScreen: where take() renders, from the first take() on.
  void attach(FrameSink& screen) { screen_ = &screen; }
  glm::vec3 pivot() const { return pivot_; }    // the scene's bounds' centre at rest
  float radius() const { return radius_; }      // half their diagonal
  double animationLength() const { return length_; }
  std::string label() const { return label_; }  // "mvr cpu"

  // Starts the next set of views; the one before must have been taken.
  void request(const LivePose& pose);
  // Waits for the requested views: an EPI volume, valid until the
  // request after next (two alternate); throws the render thread's error.
  // onScreen: renders them into the attached screen and gives null.
  const Image* take();
  // Seconds spent rendering quilts so far (on the render thread, or the
  // screen's commands on this one).
  double renderSeconds() const {
    std::lock_guard lock(mutex_);
    return renderSeconds_;
  }
  // Where that time went: posing the scene, and the renderer's stages.
  StageTimes stages() const {
    std::lock_guard lock(mutex_);
    return stages_;
  }

 private:
  void prepare();
  void add(const StageTimes& stages);  // under the lock
  void run();
  StageTimes renderOne(const LivePose& pose, FrameSink& views);

  RenderJob job_;
  bool onScreen_;
  FrameSink* screen_ = nullptr;
  FrameOrder order_ = FrameOrder::Epi;
  PreparedJob prepared_;
  std::optional<EpiVolumeSink> volumes_[2];
  glm::vec3 pivot_{0.0f};
  float radius_ = 1.0f;
  double length_ = 0.0;
  std::string label_;

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<LivePose> pending_;
  long requested_ = 0, done_ = 0;  // quilts asked for, and finished
  std::optional<LivePose> shown_;   // the pose the scene has now
  double renderSeconds_ = 0.0;
  StageTimes stages_;
  bool ready_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace mvr::app
