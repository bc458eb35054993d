#pragma once
// `mvr render` (scene + camera + back end -> image set with manifest) and
// `mvr stream` (the same, as the raw EPI-major stream).
namespace mvr::app {

// streamCommand: `mvr stream` (EPIs to --to) rather than `mvr render`.
// argv[1] is the command's name.
int runRender(int argc, char** argv, bool streamCommand = false);

}  // namespace mvr::app
