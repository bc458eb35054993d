#pragma once
// mvr native: a quilt to a lenticular panel's native image (issue 48).
namespace mvr::app {

int runNative(int argc, char** argv);

}  // namespace mvr::app
