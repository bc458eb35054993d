#pragma once
// Sinks that shape a rendered set for the pipelines that consume it:
// fan-out to several sinks, Looking Glass quilts, and Halle's per-EPI
// horizontal predistortion (9.1.1).
#include <string>
#include <vector>

#include "mvr/renderer.h"

namespace mvr {

// Hands every frame to each of several sinks.
class TeeSink final : public FrameSink {
 public:
  explicit TeeSink(std::vector<FrameSink*> sinks) : sinks_(std::move(sinks)) {}
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  void finish() override;

 private:
  std::vector<FrameSink*> sinks_;
};

// All views tiled in one image. Tile order follows the Looking Glass
// convention: view 0 bottom-left, left to right, then upwards; for a
// full-parallax grid each row of views is a row of tiles (row 0 at top).
class QuiltSink final : public FrameSink {
 public:
  // columns x rows tiles; 0 x 0 picks a layout close to square.
  QuiltSink(int width, int height, int views, int rows, PixelType type, int columns = 0,
            int tileRows = 0);
  void putView(int row, int view, const Image& image) override;
  const Image& quilt() const { return quilt_; }
  // e.g. "quilt_qs8x6a1.33.png" (the _qs{cols}x{rows}a{aspect} convention);
  // aspect: the display's width / height, 0 for the tiles'.
  std::string fileName(const std::string& ext, double aspect = 0.0) const;
  int columns() const { return columns_; }
  int tileRows() const { return tileRows_; }

 private:
  int width_, height_, views_, rows_, columns_, tileRows_;
  Image quilt_;
};

// Resamples every row of every view or EPI through a lookup table: output
// column x takes the value at source x = lut[x] (pixel centres at i + 0.5,
// linear interpolation, transparent outside the image).
class PredistortSink final : public FrameSink {
 public:
  PredistortSink(FrameSink& inner, std::vector<float> lut);
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  void finish() override { inner_.finish(); }

 private:
  Image apply(const Image& in) const;
  FrameSink& inner_;
  std::vector<float> lut_;
};

// Every view or EPI over a background colour (linear RGBA, straight
// alpha), in linear light: colour c a + b (1 - a), alpha a + b.a (1 - a);
// with b.a = 1 the images are opaque.
class BackgroundSink final : public FrameSink {
 public:
  BackgroundSink(FrameSink& inner, const glm::vec4& background) : inner_(inner), background_(background) {}
  void putView(int row, int view, const Image& image) override { inner_.putView(row, view, apply(image)); }
  void putEpi(int row, int scanline, const Image& epi) override { inner_.putEpi(row, scanline, apply(epi)); }
  void finish() override { inner_.finish(); }

 private:
  Image apply(const Image& in) const;
  FrameSink& inner_;
  glm::vec4 background_;
};

// One number per output column, whitespace or comma separated. Throws
// naming the file when it is missing, malformed or of the wrong length.
std::vector<float> loadPredistortionTable(const std::string& path, int width);

}  // namespace mvr
