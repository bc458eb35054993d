#pragma once
// Images a renderer hands to its sink a batch at a time, reused once the
// sink is done with them. A fresh image per view or EPI costs its page
// faults and zero-fill: on an H100 host, 640x480 x 1000 views, that was
// 0.3 s of MVR's 0.47 (docs/BENCHMARKS.md).
#include <memory>
#include <mutex>
#include <vector>

#include "mvr/image.h"

namespace mvr {

class ImagePool {
 public:
  ImagePool();
  // An image of w x h in `type` whose bytes are left from its last use
  // (the caller overwrites them all); back in the pool when the last copy
  // of the pointer goes, on whatever thread.
  std::shared_ptr<Image> take(int width, int height, PixelType type);
  // `count` of them; the pool's workers make the new ones, so that their
  // first touch of memory (page faults, zero-fill) runs side by side.
  std::vector<std::shared_ptr<Image>> take(int count, int width, int height, PixelType type);

 private:
  struct Shelf {
    std::mutex mutex;
    std::vector<Image> images;
  };
  std::unique_ptr<Image> fromShelf(int width, int height, PixelType type);
  std::shared_ptr<Image> lend(std::unique_ptr<Image> image);
  std::shared_ptr<Shelf> shelf_;
};

// Frames a sink holds for a while (a queue), in images it had held before:
// a frame handed over in place gives its pixels for a spare of its shape,
// any other is copied into a spare's memory. Thread-safe: the sink's
// worker gives images back while its producer holds new frames.
class SpareImages {
 public:
  // `frame` to keep; `taken`: the frame itself when its pixels may be
  // taken (FrameSink::putEpiInPlace), which then holds the spare's.
  Image hold(const Image& frame, Image* taken = nullptr);
  void giveBack(Image&& image);

 private:
  std::mutex mutex_;
  std::vector<Image> images_;
};

}  // namespace mvr
