#include "apps/memory_check.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "mvr/error.h"

namespace mvr::app {
namespace {

std::string gib(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(size_t(1) << 30));
  return text;
}

}  // namespace

size_t availableMemory() {
  std::ifstream meminfo("/proc/meminfo");
  for (std::string line; std::getline(meminfo, line);) {
    std::istringstream words(line);
    std::string key;
    size_t kib = 0;
    if (words >> key >> kib && key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

void checkHeldFramesFit(const HeldFrames& held, size_t available, const std::string& advice) {
  const size_t needed = held.reorderBytes + held.quiltBytes;
  if (available == 0 || needed <= available) return;
  std::string what = held.reorderBytes ? gib(held.reorderBytes) + " to reorder one row of frames" : "";
  if (held.quiltBytes) what += std::string(what.empty() ? "" : " and ") + gib(held.quiltBytes) + " for the quilt";
  fail("memory", "the job needs about " + gib(needed) + " (" + what + ") but " + gib(available) +
                     " are available: " + advice);
}

}  // namespace mvr::app
