#pragma once
// The image-based back end (de Quilletes 2018): a few source views are
// rendered with the deferred pipeline and depth peeled; their pixels become
// slices of the same slice table MVR builds from geometry, and the same EPI
// rasterizers fill every EPI from them.
#include <memory>
#include <string>

#include "mvr/backends/interp/interp_options.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

// Validates first; needs a current GL context.
std::unique_ptr<Renderer> makeInterpRenderer(const Scene& scene, PixelType type,
                                             const InterpOptions& options);

}  // namespace mvr
