#pragma once
// `mvr bench`: MVR against SVR, svr-layered and deferred in one process and
// one GL context, same scene and camera, as ratios (docs/BENCHMARKS.md).
namespace mvr::app {

// argv[1] is the command's name.
int runBench(int argc, char** argv);

}  // namespace mvr::app
