#include "mvr/frames/tone_mapped_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {
namespace {

class ToneMapSink final : public FrameSink {
 public:
  ToneMapSink(FrameSink& inner, ToneMap map, PixelType out) : inner_(inner), map_(map), out_(out) {}
  void putView(int row, int view, const Image& image) override { inner_.putView(row, view, mapped(image)); }
  void putEpi(int row, int scanline, const Image& epi) override { inner_.putEpi(row, scanline, mapped(epi)); }
  void finish() override { inner_.finish(); }

 private:
  const Image& mapped(const Image& linear) {
    if (scratch_.width != linear.width || scratch_.height != linear.height || scratch_.type != out_)
      scratch_ = Image(linear.width, linear.height, out_);
    toneMapImage(linear, map_, scratch_);
    return scratch_;
  }

  FrameSink& inner_;
  ToneMap map_;
  PixelType out_;
  Image scratch_{0, 0, PixelType::U8};
};

}  // namespace

void toneMapImage(const Image& linear, ToneMap map, Image& out) {
  if (linear.type != PixelType::F32) fail("tone map", "needs a float image");
  const Srgb8Encoder srgb;
  const size_t n = size_t(linear.width) * size_t(linear.height);
  const float* in = reinterpret_cast<const float*>(linear.bytes.data());
  parallelChunks(n, 16384, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const glm::vec3 c = toneMap(map, glm::vec3(in[4 * i], in[4 * i + 1], in[4 * i + 2]));
      const float a = in[4 * i + 3];
      if (out.type == PixelType::F32) {
        float* o = reinterpret_cast<float*>(out.bytes.data()) + 4 * i;
        o[0] = c.r, o[1] = c.g, o[2] = c.b, o[3] = a;
        continue;
      }
      uint8_t* o = out.bytes.data() + 4 * i;
      for (int k = 0; k < 3; ++k)
        o[k] = out.type == PixelType::Srgb8 ? srgb(c[k]) : uint8_t(std::lrint(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
      o[3] = uint8_t(std::lrint(std::clamp(a, 0.0f, 1.0f) * 255.0f));
    }
  });
}

ToneMappedRenderer::ToneMappedRenderer(std::unique_ptr<Renderer> hdr, ToneMap map, PixelType out)
    : inner_(std::move(hdr)), map_(map), out_(out) {}

void ToneMappedRenderer::render(const ShearingCamera& camera, FrameSink& sink, RenderStats& stats) {
  ToneMapSink mapped(sink, map_, out_);
  inner_->render(camera, mapped, stats);
}

}  // namespace mvr
