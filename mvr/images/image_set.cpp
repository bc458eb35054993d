#include "mvr/images/image_set.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>

#include "mvr/error.h"
#include "mvr/files/atomic_file.h"
#include "mvr/images/image_file.h"

namespace mvr {
namespace fs = std::filesystem;

ImageSetWriter::ImageSetWriter(std::string dir, Manifest manifest)
    : dir_(std::move(dir)), manifest_(std::move(manifest)) {
  const std::string& format = manifest_.format;
  if (format != "png" && format != "exr" && format != "tiff")
    fail("--format", "unknown format '" + format + "' (expected png, exr or tiff)");
  checkEncoding(format, manifest_.encoding());
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) fail(dir_, "cannot create output folder: " + ec.message());
  if (!fs::is_directory(dir_)) fail(dir_, "cannot create output folder: a file is in the way");
  // Find a read-only folder now, not after rendering.
  const fs::path probe = fs::path(dir_) / ".mvr_write_probe";
  if (std::FILE* f = std::fopen(probe.c_str(), "wb")) {
    std::fclose(f);
    fs::remove(probe, ec);
  } else {
    fail(dir_, std::string("cannot write into the output folder: ") + std::strerror(errno));
  }
  fs::remove(fs::path(dir_) / "manifest.json", ec);  // an old set is no longer complete
}

ImageSetWriter::~ImageSetWriter() {
  if (committed_) return;
  try {
    encoder_.wait();  // no file may appear after the clean-up
  } catch (...) {
  }
  std::error_code ec;
  for (const std::string& f : written_) fs::remove(f, ec);
}

void ImageSetWriter::submit(const std::string& name, std::function<void(const std::string& path)> write) {
  encoder_.submit([this, path = pathOf(name), write = std::move(write)] {
    write(path);
    std::lock_guard lock(writtenMutex_);
    written_.push_back(path);
  });
}

void ImageSetWriter::put(const std::string& name, const Image& image,
                         std::vector<std::pair<std::string, std::string>> attributes) {
  // The caller's image is gone after return: a copy, in a spare's memory.
  submit(name, [this, copy = spares_.hold(image), attributes = std::move(attributes)](const std::string& path) mutable {
    ImageEncoding encoding = manifest_.encoding();
    encoding.attributes = attributes;
    writeImage(copy, path, encoding);
    spares_.giveBack(std::move(copy));
  });
}

void ImageSetWriter::putExtra(const std::string& name, Image&& image,
                              std::vector<std::pair<std::string, std::string>> attributes) {
  submit(name, [this, image = std::move(image), attributes = std::move(attributes)](const std::string& path) {
    ImageEncoding encoding = manifest_.encoding();
    encoding.attributes = attributes;
    writeImage(image, path, encoding);
  });
}

void ImageSetWriter::putDepth(int row, int view, const DepthImage& depth) {
  submit(manifest_.depthName(row, view), [this, depth](const std::string& path) {
    writeDepthImage(depth, path, manifest_.encoding());
  });
}

void ImageSetWriter::putView(int row, int view, const Image& image) {
  put(manifest_.viewName(row, view), image);
}

void ImageSetWriter::putExtra(const std::string& name, const Image& image,
                              std::vector<std::pair<std::string, std::string>> attributes) {
  put(name, image, std::move(attributes));
}

void ImageSetWriter::putEncoded(const std::string& name, std::vector<unsigned char> bytes, bool afterPart) {
  submit(name, [bytes = std::move(bytes), afterPart](const std::string& path) {
    if (afterPart) finishPart(path, std::as_bytes(std::span(bytes)));
    else writeFileAtomically(path, std::as_bytes(std::span(bytes)));
  });
}

std::string ImageSetWriter::pathOf(const std::string& name) const { return (fs::path(dir_) / name).string(); }

void ImageSetWriter::putEpi(int row, int scanline, const Image& epi) {
  put(manifest_.epiName(row, scanline), epi);
}

// Files of an earlier set in the folder (view_*, epi_*, depth_*, quilt_*
// images) that this one did not write: the folder holds one set, so they
// go before the manifest says the set is complete.
size_t ImageSetWriter::removeStale(const std::vector<std::string>& othersWritten) const {
  const std::vector<std::string> mine = writtenNames();
  std::set<std::string> ours(mine.begin(), mine.end());
  ours.insert(othersWritten.begin(), othersWritten.end());
  size_t removed = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string(), ext = e.path().extension().string();
    const bool image = ext == ".png" || ext == ".exr" || ext == ".tif" || ext == ".tiff";
    const bool setFile = name.rfind("view_", 0) == 0 || name.rfind("epi_", 0) == 0 ||
                         name.rfind("depth_", 0) == 0 || name.rfind("quilt_", 0) == 0;
    if (image && setFile && e.is_regular_file(ec) && !ours.count(name) && fs::remove(e.path(), ec))
      ++removed;
  }
  return removed;
}

std::vector<std::string> ImageSetWriter::writtenNames() const {
  std::vector<std::string> names;
  for (const std::string& path : written_) names.push_back(fs::path(path).filename().string());
  return names;
}

void ImageSetWriter::commit() { commit({}); }

void ImageSetWriter::commit(const std::vector<std::string>& othersWritten) {
  flush();
  std::set<std::string> files(othersWritten.begin(), othersWritten.end());
  for (const std::string& name : writtenNames()) files.insert(name);
  manifest_.info["files"] = files.size();
  if (const size_t stale = removeStale(othersWritten)) manifest_.info["stale_files_removed"] = stale;
  manifest_.write(dir_);
  committed_ = true;
}

}  // namespace mvr
