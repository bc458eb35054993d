#include "apps/live_quilts.h"

#include "mvr/backends/backend.h"
#include "mvr/error.h"
#include "mvr/frames/frame_chain.h"
#include "mvr/scene_animation.h"
#include "mvr/scene_pose.h"

namespace mvr::app {

LiveQuilts::LiveQuilts(RenderJob job) : job_(std::move(job)) {
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

const Image& LiveQuilts::take() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return done_ == requested_ || error_; });
  if (error_) std::rethrow_exception(error_);
  return quilts_[(done_ - 1) % 2]->quilt();
}

// The render thread: the job prepared here (its GL context is this
// thread's), then one quilt per request until the destructor.
void LiveQuilts::run() {
  try {
    prepareJob(job_, prepared_);
    PreparedJob& p = prepared_;
    p.still = std::make_shared<const Scene>(p.scene);
    const Bounds bounds = p.scene.bounds();
    pivot_ = bounds.center();
    radius_ = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-6f);
    length_ = mvr::animationLength(p.scene, job_.sequence.clip);
    label_ = p.label(job_.backend);
    for (auto& q : quilts_)
      q.emplace(job_.width, job_.height, job_.views, job_.rows, job_.type, job_.quilt->columns, job_.quilt->rows);
    columns_ = quilts_[0]->columns(), tileRows_ = quilts_[0]->tileRows();
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
    QuiltSink& quilt = *quilts_[done_ % 2];
    lock.unlock();
    try {
      renderOne(pose, quilt);
    } catch (...) {
      lock.lock();
      error_ = std::current_exception();
      changed_.notify_all();
      return;
    }
    lock.lock();
    ++done_;
    changed_.notify_all();
  }
}

void LiveQuilts::renderOne(const LivePose& pose, QuiltSink& quilt) {
  PreparedJob& p = prepared_;
  poseGeometry(p.scene, *p.still, pose.move);
  poseAnimations(p.scene, pose.time, job_.sequence.clip, pose.move);
  if (!p.renderer->sceneMoved()) p.renderer = makeRenderer(job_.backend, p.scene, job_.type);
  NullSink none;
  FrameChainSpec spec = p.chainSpec(job_);
  spec.delivered = FrameOrder::View;
  FrameChain chain({.sink = &none, .quilt = &quilt, .frames = false}, spec);
  RenderStats stats;
  p.renderer->render(*p.renderCamera, chain.entry(), stats);
  chain.entry().finish();
}

}  // namespace mvr::app
