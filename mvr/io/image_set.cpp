#include "mvr/io/image_set.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "mvr/error.h"
#include "mvr/io/image_file.h"

namespace mvr {
namespace fs = std::filesystem;

namespace {

std::string number(int value, int count) {
  int digits = 4;
  for (int n = count - 1; n >= 10000; n /= 10) ++digits;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%0*d", digits, value);
  return buf;
}

std::string rowNumber(int row) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "r%03d", row);
  return buf;
}

}  // namespace

ImageSetWriter::ImageSetWriter(std::string dir, std::string format, int views, int rows, int height,
                               int bits)
    : dir_(std::move(dir)), format_(std::move(format)), views_(views), rows_(rows), height_(height),
      bits_(bits) {
  if (format_ != "png" && format_ != "exr" && format_ != "tiff")
    fail("--format", "unknown format '" + format_ + "' (expected png, exr or tiff)");
  if (bits_ != 8 && bits_ != 16) fail("--bits", "expected 8 or 16");
  if (bits_ == 16 && format_ == "exr") fail("--bits", "exr is always 32-bit float");
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) fail(dir_, "cannot create output folder");
  fs::remove(fs::path(dir_) / "manifest.json", ec);  // an old set is no longer complete
}

ImageSetWriter::~ImageSetWriter() {
  if (committed_) return;
  std::error_code ec;
  for (const std::string& f : written_) fs::remove(f, ec);
}

std::string ImageSetWriter::viewName(int row, int view, int views, int rows, const std::string& ext) {
  if (rows == 1) return "view_" + number(view, views) + "." + ext;
  return "view_" + rowNumber(row) + "_c" + number(view, views) + "." + ext;
}

std::string ImageSetWriter::epiName(int row, int scanline, int height, int rows,
                                    const std::string& ext) {
  if (rows == 1) return "epi_" + number(scanline, height) + "." + ext;
  return "epi_" + rowNumber(row) + "_" + number(scanline, height) + "." + ext;
}

void ImageSetWriter::putView(int row, int view, const Image& image) {
  std::string path = (fs::path(dir_) / viewName(row, view, views_, rows_, format_)).string();
  writeImage(image, path, bits_);
  written_.push_back(path);
}

void ImageSetWriter::putExtra(const std::string& name, const Image& image) {
  std::string path = (fs::path(dir_) / name).string();
  writeImage(image, path, bits_);
  written_.push_back(path);
}

void ImageSetWriter::putEpi(int row, int scanline, const Image& epi) {
  std::string path = (fs::path(dir_) / epiName(row, scanline, height_, rows_, format_)).string();
  writeImage(epi, path, bits_);
  written_.push_back(path);
}

void ImageSetWriter::commit(const nlohmann::json& manifest) {
  const fs::path path = fs::path(dir_) / "manifest.json";
  const fs::path tmp = fs::path(dir_) / "manifest.json.part";
  {
    std::ofstream out(tmp);
    out << manifest.dump(2) << "\n";
    if (!out) fail(tmp.string(), "cannot write manifest");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) fail(path.string(), "cannot write manifest: " + ec.message());
  committed_ = true;
}

}  // namespace mvr
