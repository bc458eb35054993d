#include "epi/epi_rasterizer.h"

#include "mvr/error.h"

namespace mvr {

void EpiRasterizer::rasterize(const GpuVertices&, const GpuSliceTable&, const ShearingCamera&, int,
                              FrameSink&, RenderStats&) {
  fail("EPI rasterizer", "this rasterizer reads host vertices and tables only");
}

std::unique_ptr<EpiRasterizer> makeRasterizer(PstMode mode, PixelType type, const EpiShading& shading,
                                              PstBuilder builder) {
  if (mode == PstMode::Cpu) return makeSpanRasterizer(type, shading);
  if (mode == PstMode::Spans) return makeGpuSpanRasterizer(type, shading);
  return makeGlRasterizer(mode, type, shading, builder);
}

}  // namespace mvr
