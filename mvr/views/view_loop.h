#pragma once
// The view-major loop the baselines share: draw a view, read it back
// through a readback ring (the next views are drawn while earlier ones
// travel), hand each to the sink in order. Where the sink lends a texture
// of views (FrameSink::viewTexture: mvr live's screen), each view is
// copied into its layer on the GPU instead, and nothing is read back.
#include <memory>

#include "mvr/gl/gpu_clock.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/gl/render_target.h"
#include "mvr/image_pool.h"
#include "mvr/renderer.h"

namespace mvr {

// draw(row, view) renders one view into target.
template <class Draw>
void renderEachView(const ShearingCamera& cam, const RenderTarget& target,
                    FrameSink& sink, RenderStats& stats, Draw&& draw) {
  const PixelType type = target.type();
  const RenderShare& share = cam.share();
  const bool oneRow = share.rows.size() == 1;
  if (const GLuint layers = oneRow && target.copiesBytes() ? sink.viewTexture(share.rows.begin, target.width(),
                                                                             target.height(), cam.views(), type)
                                                           : 0) {
    for (int view = share.views.begin; view < share.views.end; ++view) {
      gl::GpuClock::mark("draw");
      draw(share.rows.begin, view);
      target.copyToLayer(layers, view);  // ordered before later fetches, as every GL command
    }
    stats.notes["views"] = "texture";
    return;
  }
  ReadbackRing ring(size_t(target.width()) * target.height() * 4 * Image::channelBytes(type));
  ImagePool pool;
  for (int row = share.rows.begin; row < share.rows.end; ++row) {
    for (int view = share.views.begin; view < share.views.end; ++view) {
      gl::GpuClock::mark("draw");
      draw(row, view);
      std::shared_ptr<Image> img = pool.take(target.width(), target.height(), type);
      {
        ScopedStage s(stats.times, "readback");
        gl::GpuClock::mark("readback");
        ring.readRows(target, 0, target.height(), reinterpret_cast<std::byte*>(img->row(0)));
      }
      ring.submit([img, row, view, &sink] { sink.putView(row, view, *img); });
    }
  }
  ring.drain();
  stats.times.add("gpu_wait", ring.waitSeconds());
}

}  // namespace mvr
