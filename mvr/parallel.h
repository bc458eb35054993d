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

// parallelFor(begin, end, body) on the pool while the caller runs `beside`
// (a pipeline's serial stage: handing the previous batch on while the next
// is computed); returns when both are done. An exception of either
// propagates, body's first.
void parallelForBeside(int begin, int end, const std::function<void(int)>& body,
                       const std::function<void()>& beside);

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
