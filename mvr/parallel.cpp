#include "mvr/parallel.h"

#include <sched.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

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

void parallelForBeside(int begin, int end, const std::function<void(int)>& body,
                       const std::function<void()>& beside) {
  tbb::task_group group;
  group.run([&] { parallelFor(begin, end, body); });
  std::exception_ptr besideError;
  try {
    beside();
  } catch (...) {
    besideError = std::current_exception();
  }
  group.wait();  // the caller helps; rethrows body's exception
  if (besideError) std::rethrow_exception(besideError);
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
