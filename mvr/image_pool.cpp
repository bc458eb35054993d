#include "mvr/image_pool.h"

#include <utility>

namespace mvr {

ImagePool::ImagePool() : shelf_(std::make_shared<Shelf>()) {}

std::shared_ptr<Image> ImagePool::take(int width, int height, PixelType type) {
  Image* image = nullptr;
  {
    std::lock_guard lock(shelf_->mutex);
    auto& shelf = shelf_->images;
    for (size_t k = 0; k < shelf.size(); ++k)
      if (shelf[k].width == width && shelf[k].height == height && shelf[k].type == type) {
        image = new Image(std::move(shelf[k]));
        shelf[k] = std::move(shelf.back());
        shelf.pop_back();
        break;
      }
  }
  if (!image) image = new Image(width, height, type);
  // The deleter holds the shelf: an image outliving the pool still frees.
  return std::shared_ptr<Image>(image, [shelf = shelf_](Image* done) {
    {
      std::lock_guard lock(shelf->mutex);
      shelf->images.push_back(std::move(*done));
    }
    delete done;
  });
}

}  // namespace mvr
