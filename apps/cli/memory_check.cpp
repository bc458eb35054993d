#include "apps/cli/memory_check.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "mvr/error.h"

namespace mvr::app {
namespace {

std::string gib(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(size_t(1) << 30));
  return text;
}

// "MiB" for small sizes, where GiB would print 0.0.
std::string size(size_t bytes) {
  if (bytes >= size_t(1) << 30) return gib(bytes);
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(size_t(1) << 20));
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
  std::string what = held.reorderBytes ? gib(held.reorderBytes) + " to reorder frames" : "";
  if (held.quiltBytes) what += std::string(what.empty() ? "" : " and ") + gib(held.quiltBytes) + " for the quilt";
  fail("memory", "the job needs about " + gib(needed) + " (" + what + ") but " + gib(available) +
                     " are available: " + advice);
}

size_t parseByteSize(const std::string& flag, const std::string& text) {
  if (text.empty()) fail(flag, "is empty (e.g. 512M, 2G or a number of bytes)");
  double value = 0;
  const char* end = text.data() + text.size();
  auto [p, ec] = std::from_chars(text.data(), end, value);
  std::string unit(p, end);
  for (char& c : unit) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (unit.size() > 1 && unit.back() == 'b') unit.pop_back();  // "GB", "GiB"
  if (unit.size() > 1 && unit.back() == 'i') unit.pop_back();
  if (unit == "b") unit.clear();
  const size_t at = unit.size() == 1 ? std::string_view("kmgt").find(unit[0]) : std::string::npos;
  if (ec != std::errc() || !std::isdigit(static_cast<unsigned char>(text[0])) ||
      (!unit.empty() && at == std::string::npos) || !std::isfinite(value))
    fail(flag, "'" + text + "' is not a size (e.g. 512M, 2G or a number of bytes)");
  const int power = unit.empty() ? 0 : int(at) + 1;
  const double bytes = std::ldexp(value, 10 * power);
  if (bytes < 1 || bytes > 0x1p62) fail(flag, "'" + text + "' is out of range");
  return size_t(bytes);
}

void MemoryFlags::add(CLI::App& app, const std::string& scratchDefault) {
  app.add_option("--memory", budget,
                 "memory the frames held for reordering may take (512M, 2G ...; default: half "
                 "the available memory); beyond it 8-bit PNG views' bytes go to their files early, "
                 "other frames through a scratch file")
      ->type_name("BUDGET");
  app.add_option("--scratch", scratch, "folder for the scratch file (default: " + scratchDefault + ")")
      ->type_name("DIR");
}

size_t MemoryFlags::budgetBytes() const {
  return budget.empty() ? availableMemory() / 2 : parseByteSize("--memory", budget);
}

ReorderMemory MemoryFlags::reorder(size_t frameBytes, int inFlight,
                                   const std::string& scratchDefault) const {
  const size_t total = budgetBytes();
  const size_t encoders = frameBytes * size_t(inFlight) * 2;
  ReorderMemory memory{.budget = 0, .scratchDir = scratch.empty() ? scratchDefault : scratch};
  if (total == 0) return memory;
  if (total < encoders + frameBytes)
    fail("--memory", size(total) + " cannot hold one frame (" + size(frameBytes) +
                         ") beside the encoders' queue (" + size(encoders) + "); give at least " +
                         size(encoders + frameBytes) + " or fewer --threads");
  memory.budget = total - encoders;
  return memory;
}

void checkScratchFits(size_t bytes, const std::string& dir) {
  std::error_code ec;
  const auto space = std::filesystem::space(dir, ec);
  if (ec) fail(dir, "cannot use as scratch folder: " + ec.message());
  if (bytes > space.available)
    fail(dir, "the scratch file needs " + gib(bytes) + " but the disk has " + gib(space.available) +
                  " free: use --scratch on a larger disk, fewer views or a smaller size");
}

}  // namespace mvr::app
