#pragma once
// One thread pool for the whole program (oneTBB's task arena), as pbrt-v4's
// ParallelFor: slicing, the CPU span rasterizer and encoding share its
// workers instead of spawning threads per call.
#include <functional>
#include <memory>

namespace mvr {

// Workers the pool runs (all cores unless setThreadCount said otherwise).
int threadCount();
// The CPUs this process may run on (its affinity mask: taskset, a
// cgroup's cpuset, mpirun's binding), at most the machine's.
int availableCores();
// Limits the pool to n workers for the rest of the program; 0: all cores.
void setThreadCount(int n);
// Starts the workers now instead of at the first parallel loop: their
// start-up loads a library (TBB's allocator), so it must not come while
// another thread holds the dynamic loader (preloadImageCodec).
void startPool();
// body(i) for every i in [begin, end), one index per task, in any order
// and on any worker; returns when all are done. Exceptions propagate.
void parallelFor(int begin, int end, const std::function<void(int)>& body);
// body(begin, end) over [0, n) in chunks of `chunk` items, each chunk a
// task: per-item work too small to be a task of its own (vertices).
template <class Body>
void parallelChunks(size_t n, size_t chunk, Body&& body) {
  parallelFor(0, int((n + chunk - 1) / chunk), [&](int c) {
    body(size_t(c) * chunk, n < size_t(c + 1) * chunk ? n : size_t(c + 1) * chunk);
  });
}

// An ordered pipeline without barriers: make(i) for every i in [begin,
// end) on the pool, at most `window` indices ahead of the caller, which
// runs take(i) on its own thread in increasing order of i as each is made
// (sinks that must stay on the main thread: MPI, GL). make(i) may reuse
// the storage of i - window: take(i - window) has returned by then. The
// caller makes items too while it waits, so one thread is enough. Returns
// when every item is taken; the first exception of make or take stops the
// rest and propagates.
void parallelOrdered(int begin, int end, int window, const std::function<void(int)>& make,
                     const std::function<void(int)>& take);

// Tasks run on the pool's workers while the caller goes on (image encoding
// beside rendering), at most `limit` queued or running at once: beyond
// that submit() runs queued tasks itself until they are done, which bounds
// the memory the tasks hold. wait() helps run them and rethrows the first
// task's exception; so does the next submit() once a task has failed.
class BoundedTasks {
 public:
  explicit BoundedTasks(int limit = 0);  // 0: defaultLimit()
  static int defaultLimit();             // twice the pool's workers
  ~BoundedTasks();                       // waits; errors are dropped
  BoundedTasks(const BoundedTasks&) = delete;
  BoundedTasks& operator=(const BoundedTasks&) = delete;

  void submit(std::function<void()> task);
  void wait();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mvr
