#pragma once
// Anti-aliasing shared by every back end: the renderer draws a camera with
// more pixels and more views than asked for, and a sink box-filters the
// samples down, so svr, deferred, mvr, interp and warp are filtered alike
// and stay comparable. Halle (5.6.5): an EPI filters in space along its
// rows and in perspective down its columns; vertical filtering takes
// several EPIs, "supersample the scene vertically, render more EPIs, and
// filter the final image data to a smaller size".
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mvr/renderer.h"

namespace mvr {

struct Supersampling {
  int spatial = 1;  // S: S x S samples per pixel
  int views = 1;    // P: samples per view along the track (perspective)

  bool active() const { return spatial > 1 || views > 1; }
  int samplesPerPixel() const { return spatial * spatial * views; }
};

// The camera whose pixels and views are the samples of `camera`'s: S times
// the pixels on the same image-plane rectangle, so sample (i, j) of pixel
// (x, y) has its centre at (x + (i + 0.5) / S, y + (j + 0.5) / S); and P
// eyes per view, spread over the view's share of the track, centred on
// its eye: view v's samples at x_v + (k + 0.5 - P / 2) s / P, s the view
// spacing. Rows of a grid are not supersampled. Throws mvr::Error for
// perspective samples of a single view (it has no spacing) and for a
// camera beyond Limits.
ShearingCamera supersampledCamera(const ShearingCamera& camera, const Supersampling& aa);

// The samples of a share of `camera`'s set (a rank's share of a split
// job): its scanlines' S sample scanlines each and its views' P sample
// views each, so the share's output frames complete within it.
RenderShare sampleShare(const RenderShare& share, const Supersampling& aa);

// Box-filters frames of supersampledCamera(camera, aa) to camera's size and
// hands them on: a view from P sample views of S x S samples per pixel, an
// EPI from S sample EPIs of S x P samples per pixel. Averages in linear
// light weighted by alpha (colour: sum c a / sum a; alpha: the mean), so a
// half-covered edge pixel keeps the object's colour at half alpha. Frames
// may come in any order; a frame is handed on when its last sample frame
// arrives.
class SupersampleSink final : public FrameSink {
 public:
  // width, height, views: the output camera's.
  SupersampleSink(FrameSink& inner, const Supersampling& aa, int width, int height, int views);
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  // Throws std::logic_error when a frame is missing samples.
  void finish() override;

 private:
  struct Pending {
    std::vector<float> sums;  // premultiplied r, g, b and a per output pixel
    int frames = 0;
  };
  // Adds a sample frame into an output frame of outWidth x outHeight whose
  // pixel (x, y) takes input columns x S.. and rows y rowFactor...
  void accumulate(Pending& p, const Image& in, int outWidth, int outHeight, int rowFactor);
  Image resolve(const Pending& p, int outWidth, int outHeight, PixelType type) const;
  Pending& pending(std::map<std::pair<int, int>, Pending>& frames, int row, int index, size_t pixels);
  // Adds a sample frame to output frame `index`; the output once its
  // `needed` sample frames are in.
  std::optional<Image> add(std::map<std::pair<int, int>, Pending>& frames, int row, int index, const Image& in,
                           int outHeight, int rowFactor, int needed);

  FrameSink& inner_;
  Supersampling aa_;
  int width_, height_, views_;
  std::map<std::pair<int, int>, Pending> viewFrames_, epiFrames_;  // by (row, output index)
};

// "4x4 samples per pixel, 2 per view (box filter)": for logs and manifests.
std::string describe(const Supersampling& aa);

}  // namespace mvr
