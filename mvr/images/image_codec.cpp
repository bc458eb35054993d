#include "mvr/images/image_codec.h"

#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>

#include "mvr/error.h"
#include "mvr/timer.h"

namespace mvr {
namespace {

std::string modulePath() {
  if (const char* path = std::getenv("MVR_IMAGE_CODEC"); path && *path) return path;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) fail("image codec", "cannot find the running program: " + ec.message());
  return (self.parent_path().parent_path() / "lib" / "libmvr_oiio.so").string();
}

// The outcome of the one load: the table, or the reason there is none.
struct Loaded {
  const ImageCodec* codec = nullptr;
  std::string error;
};

std::atomic<double>& loadSeconds() {
  static std::atomic<double> seconds{0.0};
  return seconds;
}

Loaded tryLoad() {
  try {
    const std::string path = modulePath();
    // Kept loaded for the rest of the program.
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) return {nullptr, path + ": cannot load the image codec module: " + dlerror()};
    auto entry = reinterpret_cast<const ImageCodec* (*)()>(dlsym(module, "mvrImageCodec"));
    if (!entry) return {nullptr, path + ": not the image codec module (no mvrImageCodec)"};
    return {entry(), ""};
  } catch (const std::exception& e) {
    return {nullptr, e.what()};
  }
}

Loaded load() {
  const Stopwatch watch;
  Loaded loaded = tryLoad();
  loadSeconds() = watch.seconds();
  return loaded;
}

// Started once, by a preload or by the first use.
std::shared_future<Loaded>& loading() {
  static std::shared_future<Loaded> future;
  return future;
}

std::once_flag& started() {
  static std::once_flag flag;
  return flag;
}

void start(std::launch policy) {
  std::call_once(started(), [policy] { loading() = std::async(policy, load).share(); });
}

}  // namespace

void preloadImageCodec() { start(std::launch::async); }

double imageCodecLoadSeconds() { return loadSeconds().load(); }

const ImageCodec& imageCodec() {
  start(std::launch::deferred);  // runs on this thread at get() unless a preload started it
  const Loaded& loaded = loading().get();
  if (!loaded.codec) throw Error(loaded.error);
  return *loaded.codec;
}

}  // namespace mvr
