#include "mvr/parallel.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

namespace mvr {
namespace {

// Alive for the rest of the program once set: TBB honours the limit while
// a global_control object exists.
std::unique_ptr<tbb::global_control>& limit() {
  static std::unique_ptr<tbb::global_control> control;
  return control;
}

}  // namespace

int availableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1, int(std::thread::hardware_concurrency()));
}

int threadCount() {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

void setThreadCount(int n) {
  limit().reset();
  if (n > 0) limit() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(n));
}

void startPool() {
  tbb::parallel_for(0, std::max(2, threadCount()), [](int) {});
}

void parallelFor(int begin, int end, const std::function<void(int)>& body) {
  if (end - begin == 1) return body(begin);  // no task overhead for one item
  tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i < r.end(); ++i) body(i);
  });
}

namespace {

// parallelOrdered's shared state. Items are claimed in order from one
// counter, up to a limit the caller raises as it takes; each slot records
// the last index made in it, which the caller waits on.
class OrderedItems {
 public:
  OrderedItems(int begin, int end, int window, const std::function<void(int)>& make)
      : make_(make), next_(begin), limit_(std::min(end, begin + window)), end_(end), made_(size_t(window)) {
    for (std::atomic<int>& m : made_) m.store(begin - 1, std::memory_order_relaxed);
  }

  // Makes the next claimable item; false when none may be claimed now.
  bool makeOne() {
    int i = next_.load(std::memory_order_relaxed);
    do {
      if (stopped_.load(std::memory_order_relaxed) || i >= limit_.load(std::memory_order_acquire)) return false;
    } while (!next_.compare_exchange_weak(i, i + 1, std::memory_order_relaxed));
    try {
      make_(i);
    } catch (...) {
      fail(std::current_exception());
    }
    std::atomic<int>& slot = made_[size_t(i) % made_.size()];
    slot.store(i, std::memory_order_release);
    slot.notify_one();
    return true;
  }

  // Returns once item i is made, making others meanwhile.
  void awaitMade(int i) {
    std::atomic<int>& slot = made_[size_t(i) % made_.size()];
    for (int seen = slot.load(std::memory_order_acquire); seen != i; seen = slot.load(std::memory_order_acquire))
      if (!makeOne()) slot.wait(seen, std::memory_order_acquire);  // i is being made elsewhere
  }

  // Item i is taken: i + window may be claimed. False when nothing more can be.
  bool release(int i) {
    const int limit = std::min(end_, i + 1 + int(made_.size()));
    limit_.store(limit, std::memory_order_release);
    return limit > i + int(made_.size());
  }

  void fail(std::exception_ptr e) {
    std::lock_guard lock(mutex_);
    if (!error_) error_ = e;
    stopped_.store(true, std::memory_order_relaxed);
  }
  bool failed() const { return stopped_.load(std::memory_order_relaxed); }
  void rethrow() {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  const std::function<void(int)>& make_;
  std::atomic<int> next_, limit_;
  const int end_;
  std::vector<std::atomic<int>> made_;
  std::atomic<bool> stopped_{false};
  std::mutex mutex_;
  std::exception_ptr error_;
};

}  // namespace

void parallelOrdered(int begin, int end, int window, const std::function<void(int)>& make,
                     const std::function<void(int)>& take) {
  if (end <= begin) return;
  window = std::max(1, std::min(window, end - begin));
  OrderedItems items(begin, end, window, make);
  tbb::task_group group;
  // One task per claimable item; a task finding its item taken by the
  // caller returns at once. Tasks never wait, so a worker is never held
  // by a caller busy in take() (whose own parallel loops need workers).
  auto spawn = [&] { group.run([&items] { items.makeOne(); }); };
  for (int k = 0; k < window; ++k) spawn();
  for (int i = begin; i < end && !items.failed(); ++i) {
    items.awaitMade(i);
    if (items.failed()) break;
    try {
      take(i);
    } catch (...) {
      items.fail(std::current_exception());
      break;
    }
    if (items.release(i)) spawn();
  }
  group.wait();
  items.rethrow();
}

struct BoundedTasks::State {
  tbb::task_group group;
  std::mutex mutex;
  int inFlight = 0, limit = 1;
  std::exception_ptr error;

  void rethrow() {  // with mutex held
    if (!error) return;
    std::exception_ptr e = std::exchange(error, nullptr);
    std::rethrow_exception(e);
  }
};

int BoundedTasks::defaultLimit() { return 2 * threadCount(); }

BoundedTasks::BoundedTasks(int limit) : state_(std::make_unique<State>()) {
  state_->limit = limit > 0 ? limit : defaultLimit();
}

BoundedTasks::~BoundedTasks() { state_->group.wait(); }

void BoundedTasks::submit(std::function<void()> task) {
  State& s = *state_;
  bool full = false;
  {
    std::lock_guard lock(s.mutex);
    s.rethrow();
    full = s.inFlight >= s.limit;
  }
  // Full: the caller runs queued tasks until all are done (with one thread
  // it is the only one that can).
  if (full) s.group.wait();
  {
    std::lock_guard lock(s.mutex);
    s.rethrow();
    ++s.inFlight;
  }
  s.group.run([&s, task = std::move(task)] {
    std::exception_ptr failure;
    try {
      task();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard lock(s.mutex);
    if (failure && !s.error) s.error = failure;
    --s.inFlight;
  });
}

void BoundedTasks::wait() {
  state_->group.wait();
  std::lock_guard lock(state_->mutex);
  state_->rethrow();
}

}  // namespace mvr
