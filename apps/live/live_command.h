#pragma once
// mvr live: the scene rendered every frame into a quilt and shown through
// a lenticular display's mapping, in a window or headless (issue 48).
namespace mvr::app {

int runLive(int argc, char** argv);

}  // namespace mvr::app
