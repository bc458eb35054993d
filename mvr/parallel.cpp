#include "mvr/parallel.h"

#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace mvr {
namespace {

// Alive for the rest of the program once set: TBB honours the limit while
// a global_control object exists.
std::unique_ptr<tbb::global_control>& limit() {
  static std::unique_ptr<tbb::global_control> control;
  return control;
}

}  // namespace

int threadCount() {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

void setThreadCount(int n) {
  limit().reset();
  if (n > 0) limit() = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(n));
}

void parallelFor(int begin, int end, const std::function<void(int)>& body) {
  if (end - begin == 1) return body(begin);  // no task overhead for one item
  tbb::parallel_for(tbb::blocked_range<int>(begin, end, 1), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i < r.end(); ++i) body(i);
  });
}

}  // namespace mvr
