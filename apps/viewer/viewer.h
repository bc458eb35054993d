#pragma once
// `mvr view`: look at a rendered set (or a scene rendered on the spot):
// scrub through the views, see the EPI of the scanline under the cursor,
// save screenshots.
namespace mvr::app {

// argv[1] is the command's name.
int runView(int argc, char** argv);

}  // namespace mvr::app
