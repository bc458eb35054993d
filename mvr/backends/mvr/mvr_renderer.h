#pragma once
// Multiple viewpoint rendering (Halle 1997): per row of views, transform
// once to the extreme views, build the slice table, rasterize every EPI.
#include <memory>

#include "epi/epi_rasterizer.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

// GL modes need a current context; cpu runs on the thread pool and always
// samples textures directly.
std::unique_ptr<Renderer> makeMvrRenderer(const Scene& scene, PstMode mode, PixelType type,
                                          TextureMode texture = TextureMode::Vector,
                                          PstBuilder builder = PstBuilder::Auto);

}  // namespace mvr
