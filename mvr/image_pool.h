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

}  // namespace mvr
