#pragma once
// A back end rendering linear HDR radiance in float whose frames reach the
// sinks tone mapped (`--tonemap`, mvr/tone_map.h) and encoded to the
// output's pixel type: Srgb8 (sRGB-encoded), U8 (linear, --linear) or F32
// (the display values, for 16-bit PNG and TIFF). One place for every back
// end, views and EPIs alike; the sinks' zero-copy paths (EPI memory and
// textures) are not offered, so each frame is handed on once.
#include <memory>

#include "mvr/renderer.h"
#include "mvr/tone_map.h"

namespace mvr {

class ToneMappedRenderer final : public Renderer {
 public:
  // `hdr` renders F32; its frames are tone mapped by `map` into `out`.
  ToneMappedRenderer(std::unique_ptr<Renderer> hdr, ToneMap map, PixelType out);

  std::string name() const override { return inner_->name(); }
  FrameOrder order() const override { return inner_->order(); }
  void render(const ShearingCamera& camera, FrameSink& sink, RenderStats& stats) override;
  bool sceneMoved() override { return inner_->sceneMoved(); }

 private:
  std::unique_ptr<Renderer> inner_;
  ToneMap map_;
  PixelType out_;
};

// An F32 image tone mapped into one of `out`: alpha kept as it is.
void toneMapImage(const Image& linear, ToneMap map, Image& out);

}  // namespace mvr
