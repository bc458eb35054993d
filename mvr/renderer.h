#pragma once
// The public rendering API: every back end renders the same Scene through
// the same ShearingCamera and hands finished frames to a FrameSink.
#include <map>
#include <memory>
#include <string>

#include "mvr/camera.h"
#include "mvr/image.h"
#include "mvr/timer.h"

namespace mvr {

// Receives frames as a back end finishes them. View renderers (SVR,
// deferred) produce views; EPI renderers (MVR, interp) produce EPIs, one
// scanline seen from every view of a row: W x N pixels, row i = view i.
// Adaptors in mvr/frames/volume.h turn one order into the other.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  virtual void putView(int row, int view, const Image& image);
  virtual void putEpi(int row, int scanline, const Image& epi);
  // An EPI its producer is done with: the sink may change it in place
  // before handing it on (interp's source rows), or take its pixels and
  // leave another image of the same size and type in their place (the EPI
  // stream's queue), instead of copying it. The producer writes every
  // pixel again before it hands the image on again.
  virtual void putEpiInPlace(int row, int scanline, Image& epi) { putEpi(row, scanline, epi); }
  // Memory where the producer may write EPI (row, scanline) itself: width
  // x views pixels of `type`, rows contiguous, owned by the sink and valid
  // until the producer's call that asked for it returns. Once that call
  // returns the EPI is complete there, and the producer does not hand it
  // on. Null (the default): the producer fills an image of its own and
  // hands it on. For a sink that would copy each EPI into a larger image
  // (interp's pieces into the EPIs of all views): the copy goes.
  virtual uint8_t* epiMemory(int /*row*/, int /*scanline*/, int /*width*/, int /*views*/, PixelType) {
    return nullptr;
  }
  // A GL texture of the current context where the producer may write
  // every EPI of row `row` itself, on the GPU: a 2D array of width x views
  // RGBA8 layers, layer s scanline s's EPI (row v view v's). Once the
  // producer's render() returns, its GL commands have written every EPI
  // there (nothing handed on) and made them visible to texture fetches.
  // 0 (the default): none; and for a type that is not 8-bit.
  virtual unsigned epiTexture(int /*row*/, int /*width*/, int /*views*/, PixelType) { return 0; }
  // The same for a view renderer: a 2D array of `views` width x height
  // RGBA8 layers, layer v view v with its rows top first (as read back).
  virtual unsigned viewTexture(int /*row*/, int /*width*/, int /*height*/, int /*views*/, PixelType) { return 0; }
  virtual void finish() {}
};

// Discards frames (benchmarks that only time the rendering).
class NullSink final : public FrameSink {
 public:
  void putView(int, int, const Image&) override {}
  void putEpi(int, int, const Image&) override {}
};

struct RenderStats {
  StageTimes times;
  std::map<std::string, double> counters;  // slices, bytes, layers, ...
  std::map<std::string, std::string> notes; // passes run, options
};

enum class FrameOrder { View, Epi };

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual std::string name() const = 0;
  virtual FrameOrder order() const = 0;
  // All rows x views of the camera, in the renderer's natural order.
  virtual void render(const ShearingCamera& camera, FrameSink& sink, RenderStats& stats) = 0;
  // The scene it renders moved in place (mvr/scene_pose.h: new positions
  // and normals, the same vertices, triangles and materials): derive again
  // what depends on them before the next render. False: this renderer
  // cannot follow; the caller makes a new one.
  virtual bool sceneMoved() { return false; }
};

}  // namespace mvr
