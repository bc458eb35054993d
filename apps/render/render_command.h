#pragma once
// `mvr render` (scene + camera + back end -> image set with manifest),
// `mvr stream` (the same, as the raw EPI-major stream) and `mvr
// synthesize` (RGB-D references + camera -> the same outputs, by the
// depth-image warping back end).
namespace mvr::app {

// argv[1] is the command's name.
int runRender(int argc, char** argv);
int runStream(int argc, char** argv);
int runSynthesize(int argc, char** argv);

}  // namespace mvr::app
