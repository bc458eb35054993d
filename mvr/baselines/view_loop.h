#pragma once
// The view-major loop the baselines share: draw a view, read it back, hand
// it to the sink, report progress.
#include "mvr/gl/render_target.h"
#include "mvr/progress.h"
#include "mvr/renderer.h"

namespace mvr {

// draw(row, view) renders one view into target.
template <class Draw>
void renderEachView(const ShearingCamera& cam, const RenderTarget& target, const char* label,
                    FrameSink& sink, RenderStats& stats, Draw&& draw) {
  Progress progress(label, long(cam.rows()) * cam.views());
  for (int row = 0; row < cam.rows(); ++row) {
    for (int view = 0; view < cam.views(); ++view) {
      draw(row, view);
      Image img;
      {
        ScopedStage s(stats.times, "readback");
        img = target.read();
      }
      sink.putView(row, view, img);
      progress.step();
    }
  }
}

}  // namespace mvr
