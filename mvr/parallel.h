#pragma once
// One thread pool for the whole program (oneTBB's task arena), as pbrt-v4's
// ParallelFor: slicing, the CPU span rasterizer and encoding share its
// workers instead of spawning threads per call.
#include <functional>

namespace mvr {

// Workers the pool runs (all cores unless setThreadCount said otherwise).
int threadCount();
// Limits the pool to n workers for the rest of the program; 0: all cores.
void setThreadCount(int n);
// body(i) for every i in [begin, end), one index per task, in any order
// and on any worker; returns when all are done. Exceptions propagate.
void parallelFor(int begin, int end, const std::function<void(int)>& body);

}  // namespace mvr
