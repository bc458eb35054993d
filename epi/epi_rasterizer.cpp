#include "epi/epi_rasterizer.h"

namespace mvr {

std::unique_ptr<EpiRasterizer> makeRasterizer(PstMode mode, PixelType type, const EpiShading& shading,
                                              PstBuilder builder) {
  return mode == PstMode::Cpu ? makeSpanRasterizer(type, shading)
                              : makeGlRasterizer(mode, type, shading, builder);
}

}  // namespace mvr
