#pragma once
// Writes a rendered set to a folder: view_0000.png ... (view_r000_c0000.png
// for grids), epi_0000.png ..., and manifest.json last; the images of an
// earlier set there that this one does not overwrite are removed. Images are encoded
// on the thread pool while rendering goes on (a bounded number queued, so
// memory stays bounded); each file appears complete or not at all. Until
// commit() the set is incomplete: if the writer is destroyed first (an
// error), every file it wrote is removed, so no half-written set looks
// finished. An encoding error surfaces at the next put or at commit().
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "mvr/image_pool.h"
#include "mvr/images/manifest.h"
#include "mvr/parallel.h"
#include "mvr/renderer.h"

namespace mvr {

class ImageSetWriter final : public FrameSink {
 public:
  // The manifest's layout names the files and its encoding says how they
  // store pixels (checkEncoding). Creates dir if needed.
  ImageSetWriter(std::string dir, Manifest manifest);
  ~ImageSetWriter() override;

  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  // A view's depth map (Manifest::depthName), float exr.
  void putDepth(int row, int view, const DepthImage& depth);
  // An extra image in the set (a quilt), removed like the rest on failure,
  // with metadata attributes (ImageEncoding::attributes).
  void putExtra(const std::string& name, const Image& image,
                std::vector<std::pair<std::string, std::string>> attributes = {});
  // The same, the image given (no copy of a 45 MB quilt).
  void putExtra(const std::string& name, Image&& image,
                std::vector<std::pair<std::string, std::string>> attributes = {});
  // A file of the set encoded elsewhere (mvr/frames/png_views.h): written on
  // the pool like the rest, removed like the rest on failure. afterPart:
  // its first bytes are in its temporary file already (appendToPart on
  // pathOf(name), mvr/files/atomic_file.h) and these are the rest.
  void putEncoded(const std::string& name, std::vector<unsigned char> bytes, bool afterPart = false);
  std::string pathOf(const std::string& name) const;
  // What commit() writes; fill its info before.
  Manifest& manifest() { return manifest_; }
  // Waits until every image put so far is on disk; rethrows an encoding
  // error.
  void flush() { encoder_.wait(); }
  // Removes the images of an earlier set this one did not overwrite, then
  // writes the manifest, last: from now on the set is complete.
  void commit();
  // A set written by several processes into one folder (apps/split_output):
  // one commits with the names of the files the others wrote, so they
  // count as the set's and are not stale; the others keep() theirs once it
  // has, without a manifest of their own.
  void commit(const std::vector<std::string>& othersWritten);
  void keep() { committed_ = true; }
  // The file names (no folder) written so far; after flush().
  std::vector<std::string> writtenNames() const;

  size_t filesWritten() const { return written_.size(); }

 private:
  void put(const std::string& name, const Image& image, std::vector<std::pair<std::string, std::string>> attributes = {});
  size_t removeStale(const std::vector<std::string>& othersWritten) const;
  // Encodes on the pool; the file is removed with the rest on failure.
  void submit(const std::string& name, std::function<void(const std::string& path)> write);

  std::string dir_;
  Manifest manifest_;
  std::mutex writtenMutex_;
  std::vector<std::string> written_;
  // Copies of the caller's frames, recycled: a fresh multi-megabyte
  // allocation per file costs page faults that serialise on the kernel's
  // memory lock and kept two cores from encoding twice as fast.
  SpareImages spares_;
  bool committed_ = false;
  BoundedTasks encoder_;  // last member: destroyed (drained) first
};

}  // namespace mvr
