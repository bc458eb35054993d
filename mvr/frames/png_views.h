#pragma once
// A row of views written as PNG files straight from its EPIs: view i's
// file row j is EPI j's row i, so each arriving EPI hands one row to every
// view's encoder (mvr/images/png_encoder.h), and each file is written as soon
// as its last row is in. Where EpisToViews (mvr/frames/volume.h) first fills the
// whole W x H x N volume (memory, its zero-fill and a copy of every pixel)
// and encodes after the last EPI, this encodes while the EPIs come and
// holds the views' compressed bytes and one deflate segment each: what a
// whole MVR render to PNG costs beyond rendering (issue 15).
//
// The rows are encoded on the pool while the producer goes on: EPIs wait
// in a short queue, fed to the encoders in scanline order by one task at
// a time (each row's views spread over the pool), so a GL renderer's
// thread keeps the GPU busy instead of waiting for the encoders; a
// producer that gets a queue's length ahead helps encode until it is
// empty.
//
// The files are byte for byte those ImageSetWriter::putView writes for
// the same views. For byte images into 8-bit PNG files and float images
// into 8- or 16-bit ones (handles()); other encodings go through
// EpisToViews.
#include <atomic>
#include <cstdint>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/task_group.h>

#include "mvr/image_pool.h"
#include "mvr/images/image_set.h"
#include "mvr/images/png_encoder.h"

namespace mvr {

class EpisToPngViews final : public FrameSink {
 public:
  // The set's files are PNGs this sink writes from EPIs of this type: byte
  // images as stored into 8-bit files, float ones into files of any bits.
  static bool handles(const Manifest& manifest, PixelType type);
  // How the views were made, as manifests say (FrameTranspose::method's kin).
  static constexpr const char* kMethod = "EPI rows into the views' PNG encoders";
  // EPIs of `type` a sink queues for encoding within `budget` bytes of
  // memory: an eighth of it, at most 128 MB, so that a GL renderer can
  // hand over a batch or two (16 EPIs at 640 x 1000) and draw the next
  // while they are encoded; 4 to 64 EPIs.
  static int queueLength(const Manifest& manifest, PixelType type, size_t budget);
  // The bytes of files a sink may hold within `budget` bytes of memory
  // beside its encoders and queue, 0 when those alone would not leave
  // room for 16 KiB per view.
  static size_t filesBudget(const Manifest& manifest, PixelType type, size_t budget);

  // The writer names, writes and records the files (putEncoded); its
  // manifest gives the size, the views per row and the zlib level. When
  // the files' bytes held exceed filesBudget, they go to the files'
  // temporary names (appendToPart) and the sink holds none again.
  EpisToPngViews(ImageSetWriter& writer, PixelType type, size_t filesBudget = SIZE_MAX, int queueLength = 4);
  // Waits for the encoding; removes the temporary files of an unfinished row.
  ~EpisToPngViews() override;
  // EPIs of a row in any order (early ones are held until their turn),
  // rows one after another. An encoding error surfaces at a later put or
  // at finish().
  void putEpi(int row, int scanline, const Image& epi) override;
  // The same, taking the EPI's pixels and leaving a spare image's.
  void putEpiInPlace(int row, int scanline, Image& epi) override;
  // Throws if a row was left with scanlines missing.
  void finish() override;
  // How often the files' bytes went to disk before their last row.
  int spills() const { return spills_; }

 private:
  void put(int row, int scanline, const Image& epi, Image* taken);
  void startRow(int row);
  void enqueue(const Image& epi, Image* taken);
  void drain();
  void settle();
  void feed(const Image& epi);
  void spill();

  ImageSetWriter& writer_;
  PngFormat format_;
  PixelType type_;
  int views_;
  size_t filesBudget_;
  int queueLength_;
  int row_ = -1, next_ = 0;  // the row being encoded, its next scanline to queue
  int fed_ = 0;              // scanlines the encoders have (the draining task's)
  std::atomic<int> spills_{0};  // counted by the draining task
  std::vector<std::vector<unsigned char>> files_;  // view i's encoded bytes not yet on disk
  std::vector<char> spilled_;                     // view i's file has bytes on disk
  std::vector<std::unique_ptr<PngEncoder>> encoders_;
  std::map<int, Image> early_;  // scanlines that came before their turn

  // The queue and its draining task: at most one drains at a time.
  std::mutex mutex_;
  std::deque<Image> queued_;
  SpareImages spares_;  // fed EPIs' images, to hold the next ones
  bool draining_ = false;
  std::exception_ptr error_;
  std::unique_ptr<tbb::task_group> lane_ = std::make_unique<tbb::task_group>();  // waited on before it goes
};

}  // namespace mvr
