#pragma once
// Writes a rendered set to a folder: view_0000.png ... (view_r000_c0000.png
// for grids), epi_0000.png ..., and manifest.json last. Until commit() the
// set is incomplete: if the writer is destroyed first (an error), every file
// it wrote is removed, so no half-written set looks finished.
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "mvr/renderer.h"

namespace mvr {

class ImageSetWriter final : public FrameSink {
 public:
  // format: png, exr or tiff; bits: 8 or 16 for png and tiff. Creates dir
  // if needed.
  ImageSetWriter(std::string dir, std::string format, int views, int rows, int height, int bits = 8);
  ~ImageSetWriter() override;

  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  // An extra image in the set (a quilt), removed like the rest on failure.
  void putExtra(const std::string& name, const Image& image);
  void commit(const nlohmann::json& manifest);

  size_t filesWritten() const { return written_.size(); }
  static std::string viewName(int row, int view, int views, int rows, const std::string& ext);
  static std::string epiName(int row, int scanline, int height, int rows, const std::string& ext);

 private:
  std::string dir_, format_;
  int views_, rows_, height_, bits_;
  std::vector<std::string> written_;
  bool committed_ = false;
};

}  // namespace mvr
