#include "mvr/frames/frame_sinks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mvr/error.h"

namespace mvr {

void TeeSink::putView(int row, int view, const Image& image) {
  for (FrameSink* s : sinks_) s->putView(row, view, image);
}
void TeeSink::putEpi(int row, int scanline, const Image& epi) {
  for (FrameSink* s : sinks_) s->putEpi(row, scanline, epi);
}
void TeeSink::finish() {
  for (FrameSink* s : sinks_) s->finish();
}

QuiltSink::QuiltSink(int width, int height, int views, int rows, PixelType type, int columns,
                     int tileRows)
    : width_(width), height_(height), views_(views), rows_(rows) {
  const int total = views * rows;
  if (columns <= 0 || tileRows <= 0) {
    if (rows > 1) {
      columns = views;
      tileRows = rows;
    } else {  // near-square quilt: columns * width ~ tileRows * height
      columns = std::max(1, int(std::lround(std::sqrt(double(total) * height / width))));
      tileRows = (total + columns - 1) / columns;
    }
  }
  if (long(columns) * tileRows < total)
    fail("--quilt", std::to_string(columns) + "x" + std::to_string(tileRows) + " tiles hold fewer than " +
                        std::to_string(total) + " views");
  if (long(columns) * width > 32768 || long(tileRows) * height > 32768)
    fail("--quilt", "quilt larger than 32768 pixels on a side");
  columns_ = columns;
  tileRows_ = tileRows;
  quilt_ = Image(columns * width, tileRows * height, type);
}

glm::ivec2 QuiltSink::tileOrigin(int row, int view) const {
  const int index = row * views_ + view;
  // Single row: view 0 bottom-left, filling upwards. Grids: row 0 on top.
  const int tileRow = rows_ > 1 ? row : tileRows_ - 1 - index / columns_;
  const int tileCol = rows_ > 1 ? view : index % columns_;
  return {tileCol * width_, tileRow * height_};
}

void QuiltSink::putView(int row, int view, const Image& image) {
  const glm::ivec2 at = tileOrigin(row, view);
  const size_t left = size_t(at.x) * (4 * Image::channelBytes(quilt_.type));
  for (int y = 0; y < height_; ++y) std::memcpy(quilt_.row(at.y + y) + left, image.row(y), image.rowBytes());
}

void QuiltSink::putEpi(int row, int scanline, const Image& epi) {
  for (int view = 0; view < views_; ++view) {
    const glm::ivec2 at = tileOrigin(row, view);
    std::memcpy(quilt_.row(at.y + scanline) + size_t(at.x) * (4 * Image::channelBytes(quilt_.type)), epi.row(view), epi.rowBytes());
  }
}

std::string QuiltSink::fileName(const std::string& ext, double aspect) const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "quilt_qs%dx%da%.2f.%s", columns_, tileRows_,
                aspect > 0.0 ? aspect : double(width_) / height_, ext.c_str());
  return buf;
}

EpiVolumeSink::EpiVolumeSink(int width, int height, int views, PixelType type)
    : views_(views), volume_(width, height * views, type) {}

void EpiVolumeSink::putView(int row, int view, const Image& image) {
  if (row != 0 || image.width != volume_.width || image.height * views_ != volume_.height)
    fail("epi volume", "a view of another size, or of a second row");
  for (int s = 0; s < image.height; ++s) std::memcpy(volume_.row(s * views_ + view), image.row(s), image.rowBytes());
}

void EpiVolumeSink::putEpi(int row, int scanline, const Image& epi) {
  uint8_t* to = epiMemory(row, scanline, epi.width, epi.height, epi.type);
  if (!to) fail("epi volume", "an EPI of another size, or of a second row");
  if (to != epi.bytes.data()) std::memcpy(to, epi.bytes.data(), epi.bytes.size());
}

uint8_t* EpiVolumeSink::epiMemory(int row, int scanline, int width, int views, PixelType type) {
  if (row != 0 || width != volume_.width || views != views_ || type != volume_.type ||
      scanline * views_ >= volume_.height)
    return nullptr;
  return volume_.row(scanline * views_);
}

PredistortSink::PredistortSink(FrameSink& inner, std::vector<float> lut)
    : inner_(inner), lut_(std::move(lut)) {}

void PredistortSink::putView(int row, int view, const Image& image) { inner_.putView(row, view, apply(image)); }
void PredistortSink::putEpi(int row, int scanline, const Image& epi) { inner_.putEpi(row, scanline, apply(epi)); }

Image PredistortSink::apply(const Image& in) const {
  if (lut_.size() != size_t(in.width)) fail("predistortion", "table width differs from the image's");
  Image out(in.width, in.height, in.type);
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      const float s = lut_[x] - 0.5f;  // continuous source coordinate of centres
      const int x0 = int(std::floor(s));
      const float t = s - float(x0);
      // Interpolated in linear light: encoded values would darken edges.
      glm::vec4 a = x0 >= 0 && x0 < in.width ? in.linear(x0, y) : glm::vec4(0);
      glm::vec4 b = x0 + 1 >= 0 && x0 + 1 < in.width ? in.linear(x0 + 1, y) : glm::vec4(0);
      out.setLinear(x, y, a + (b - a) * t);
    }
  }
  return out;
}

Image BackgroundSink::apply(const Image& in) const {
  Image out(in.width, in.height, in.type);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const glm::vec4 c = in.linear(x, y);
      const glm::vec3 rgb = glm::vec3(c) * c.a + glm::vec3(background_) * (1.0f - c.a);
      out.setLinear(x, y, glm::vec4(rgb, c.a + background_.a * (1.0f - c.a)));
    }
  return out;
}

std::vector<float> loadPredistortionTable(const std::string& path, int width) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open predistortion table");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (char& c : text)
    if (c == ',') c = ' ';
  std::istringstream values(text);
  std::vector<float> lut;
  for (std::string tok; values >> tok;) {
    char* end = nullptr;
    const float v = std::strtof(tok.c_str(), &end);
    if (*end || !std::isfinite(v)) fail(path, "entry " + std::to_string(lut.size()) + " '" + tok + "' is not a number");
    lut.push_back(v);
  }
  if (lut.size() != size_t(width))
    fail(path, std::to_string(lut.size()) + " entries, the image is " + std::to_string(width) + " wide");
  return lut;
}

}  // namespace mvr
