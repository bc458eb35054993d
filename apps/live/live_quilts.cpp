#include "apps/live/live_quilts.h"

#include <utility>

#include "mvr/error.h"
#include "mvr/frames/frame_chain.h"
#include "mvr/scene_animation.h"
#include "mvr/scene_pose.h"

namespace mvr::app {

LiveQuilts::LiveQuilts(RenderJob job, bool onScreen) : job_(std::move(job)), onScreen_(onScreen) {
  if (onScreen_) {
    job_.currentGl = true;
    prepare();
    return;
  }
  thread_ = std::thread([this] { run(); });
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return ready_ || error_; });
  if (error_) {
    lock.unlock();
    thread_.join();
    std::rethrow_exception(error_);
  }
}

LiveQuilts::~LiveQuilts() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void LiveQuilts::request(const LivePose& pose) {
  {
    std::lock_guard lock(mutex_);
    if (requested_ != done_) fail("live", "a quilt was asked for before the last one was taken");
    pending_ = pose;
    ++requested_;
  }
  changed_.notify_all();
}

const Image* LiveQuilts::take() {
  if (onScreen_) {
    if (done_ == requested_ || !screen_) fail("live", "no quilt was asked for, or no screen attached");
    const Stopwatch watch;
    const StageTimes stages = renderOne(*std::exchange(pending_, std::nullopt), *screen_);
    std::lock_guard lock(mutex_);
    renderSeconds_ += watch.seconds();
    add(stages);
    ++done_;
    return nullptr;
  }
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return done_ == requested_ || error_; });
  if (error_) std::rethrow_exception(error_);
  return &volumes_[(done_ - 1) % 2]->volume();
}

// GL (the render thread's own context, or the screen's), the scene, the
// camera and the renderer; what the viewer needs to know of the scene.
void LiveQuilts::prepare() {
  prepareJob(job_, prepared_);
  PreparedJob& p = prepared_;
  const Bounds bounds = p.scene.bounds();
  pivot_ = bounds.center();
  radius_ = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
  length_ = mvr::animationLength(p.scene, job_.sequence.clip);
  label_ = p.label(job_.backend);
  order_ = p.renderer->order();
  if (!onScreen_)
    for (auto& v : volumes_) v.emplace(job_.width, job_.height, job_.views, job_.type);
}

// The render thread: the job prepared here (its GL context is this
// thread's), then one quilt per request until the destructor.
void LiveQuilts::run() {
  try {
    prepare();
  } catch (...) {
    std::lock_guard lock(mutex_);
    error_ = std::current_exception();
    changed_.notify_all();
    return;
  }
  std::unique_lock lock(mutex_);
  ready_ = true;
  changed_.notify_all();
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || pending_; });
    if (stopping_) return;
    const LivePose pose = *pending_;
    pending_.reset();
    EpiVolumeSink& views = *volumes_[done_ % 2];
    lock.unlock();
    const Stopwatch watch;
    StageTimes stages;
    try {
      stages = renderOne(pose, views);
    } catch (...) {
      lock.lock();
      error_ = std::current_exception();
      changed_.notify_all();
      return;
    }
    lock.lock();
    renderSeconds_ += watch.seconds();
    add(stages);
    ++done_;
    changed_.notify_all();
  }
}

void LiveQuilts::add(const StageTimes& stages) {
  for (const auto& [stage, seconds] : stages.seconds) stages_.add(stage, seconds);
}

StageTimes LiveQuilts::renderOne(const LivePose& pose, FrameSink& views) {
  PreparedJob& p = prepared_;
  RenderStats stats;
  // A scene that stands still keeps its pose, and MVR its lighting.
  const bool animated = !p.scene.animations.empty();
  if (!shown_ || shown_->move != pose.move || (animated && shown_->time != pose.time)) {
    ScopedStage s(stats.times, "pose");
    poseJob(job_, p, pose.time, pose.move);
    shown_ = pose;
  }
  FrameChain chain({.sink = &views}, p.chainSpec(job_));  // in the renderer's order: the sink takes both
  p.renderer->render(*p.renderCamera, chain.entry(), stats);
  chain.entry().finish();
  return stats.times;
}

QuiltGrid liveGrid(const RenderJob& job) {
  const QuiltSink layout(1, 1, job.views, job.rows, job.type, job.quilt->columns, job.quilt->rows);
  return {layout.columns(), layout.tileRows(), job.views, job.width, job.height};
}

}  // namespace mvr::app
