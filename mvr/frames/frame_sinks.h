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
  // An EPI's rows straight into their tiles: a quilt alone needs no
  // reordering of an EPI renderer's frames.
  void putEpi(int row, int scanline, const Image& epi) override;
  const Image& quilt() const { return quilt_; }
  // The finished quilt, handed on without a copy; the sink holds none after.
  Image takeQuilt() { return std::move(quilt_); }
  // e.g. "quilt_qs8x6a1.33.png" (the _qs{cols}x{rows}a{aspect} convention);
  // aspect: the display's width / height, 0 for the tiles'.
  std::string fileName(const std::string& ext, double aspect = 0.0) const;
  int columns() const { return columns_; }
  int tileRows() const { return tileRows_; }

 private:
  // Where view `view` of row `row` starts: its tile's top row and left column.
  glm::ivec2 tileOrigin(int row, int view) const;
  int width_, height_, views_, rows_, columns_, tileRows_;
  Image quilt_;
};

// One row of views as an EPI volume (mvr/lenticular.h's
// ViewLayout::EpiVolume: width x (height x views), scanline s's EPI
// after s - 1's), what mvr live uploads: an EPI renderer writes into it in
// place (epiMemory), a view renderer's rows are scattered to their EPIs.
class EpiVolumeSink final : public FrameSink {
 public:
  EpiVolumeSink(int width, int height, int views, PixelType type);
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  uint8_t* epiMemory(int row, int scanline, int width, int views, PixelType type) override;
  const Image& volume() const { return volume_; }

 private:
  int views_;
  Image volume_;
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
