#include "mvr/image_pool.h"

#include <algorithm>
#include <utility>

#include "mvr/parallel.h"

namespace mvr {

ImagePool::ImagePool() : shelf_(std::make_shared<Shelf>()) {}

std::unique_ptr<Image> ImagePool::fromShelf(int width, int height, PixelType type) {
  std::lock_guard lock(shelf_->mutex);
  auto& shelf = shelf_->images;
  for (size_t k = 0; k < shelf.size(); ++k)
    if (shelf[k].width == width && shelf[k].height == height && shelf[k].type == type) {
      auto image = std::make_unique<Image>(std::move(shelf[k]));
      shelf[k] = std::move(shelf.back());
      shelf.pop_back();
      return image;
    }
  return nullptr;
}

// The deleter holds the shelf: an image outliving the pool still frees.
std::shared_ptr<Image> ImagePool::lend(std::unique_ptr<Image> image) {
  return std::shared_ptr<Image>(image.release(), [shelf = shelf_](Image* done) {
    {
      std::lock_guard lock(shelf->mutex);
      shelf->images.push_back(std::move(*done));
    }
    delete done;
  });
}

std::shared_ptr<Image> ImagePool::take(int width, int height, PixelType type) {
  std::unique_ptr<Image> image = fromShelf(width, height, type);
  if (!image) image = std::make_unique<Image>(width, height, type);
  return lend(std::move(image));
}

std::vector<std::shared_ptr<Image>> ImagePool::take(int count, int width, int height, PixelType type) {
  std::vector<std::unique_ptr<Image>> images(size_t(std::max(count, 0)));
  std::vector<int> fresh;
  for (int k = 0; k < count; ++k)
    if (!(images[size_t(k)] = fromShelf(width, height, type))) fresh.push_back(k);
  parallelFor(0, int(fresh.size()), [&](int k) {
    images[size_t(fresh[size_t(k)])] = std::make_unique<Image>(width, height, type);
  });
  std::vector<std::shared_ptr<Image>> out;
  for (auto& image : images) out.push_back(lend(std::move(image)));
  return out;
}

// The copy is made outside the lock (a copy under it would stall the
// worker giving images back), into memory already touched: a fresh
// multi-megabyte image per frame costs its pages' first-touch faults.
Image SpareImages::hold(const Image& frame, Image* taken) {
  Image held;
  {
    std::lock_guard lock(mutex_);
    if (!images_.empty()) held = std::move(images_.back()), images_.pop_back();
  }
  if (taken && held.width == taken->width && held.height == taken->height && held.type == taken->type &&
      held.bytes.size() == taken->bytes.size())
    std::swap(held, *taken);
  else
    held = frame;
  return held;
}

void SpareImages::giveBack(Image&& image) {
  std::lock_guard lock(mutex_);
  images_.push_back(std::move(image));
}

}  // namespace mvr
