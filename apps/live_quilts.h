#pragma once
// mvr live's renderer (issue 48): the scene's views, one set after
// another, rendered on a thread of its own with its own GL context (EGL),
// so that rendering frame k + 1 overlaps showing frame k. Each set is an
// EPI volume (mvr/lenticular.h), where an EPI renderer writes in place and
// the panel mapping finds a panel row's views close together. Two
// alternate: the one shown stays whole while the next is drawn.
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <glm/glm.hpp>

#include "apps/render_job.h"
#include "mvr/frames/frame_sinks.h"

namespace mvr::app {

// What one live frame shows: the scene's animation at `time`, then moved
// by `move` (the viewer's orbit, zoom and focal plane) in world space.
struct LivePose {
  double time = 0.0;
  glm::mat4 move{1.0f};
};

class LiveQuilts {
 public:
  // Prepares the job on the render thread (GL, scene, camera, renderer);
  // its errors are thrown here.
  explicit LiveQuilts(RenderJob job);
  ~LiveQuilts();
  LiveQuilts(const LiveQuilts&) = delete;
  LiveQuilts& operator=(const LiveQuilts&) = delete;

  const RenderJob& job() const { return job_; }
  glm::vec3 pivot() const { return pivot_; }    // the scene's bounds' centre at rest
  float radius() const { return radius_; }      // half their diagonal
  double animationLength() const { return length_; }
  std::string label() const { return label_; }  // "mvr cpu"
  int columns() const { return columns_; }
  int tileRows() const { return tileRows_; }

  // Starts the next set of views; the one before must have been taken.
  void request(const LivePose& pose);
  // Waits for the requested views (an EPI volume). They stay valid until
  // the request after next (two alternate); throws the render thread's error.
  const Image& take();
  // Seconds the render thread spent on quilts so far, and how many.
  double renderSeconds() const { return renderSeconds_; }

 private:
  void run();
  void renderOne(const LivePose& pose, EpiVolumeSink& views);

  RenderJob job_;
  PreparedJob prepared_;
  std::optional<EpiVolumeSink> volumes_[2];
  glm::vec3 pivot_{0.0f};
  float radius_ = 1.0f;
  double length_ = 0.0;
  std::string label_;
  int columns_ = 0, tileRows_ = 0;

  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<LivePose> pending_;
  long requested_ = 0, done_ = 0;  // quilts asked for, and finished
  std::optional<LivePose> shown_;   // the pose the scene has now
  double renderSeconds_ = 0.0;
  bool ready_ = false, stopping_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace mvr::app
