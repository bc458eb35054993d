#pragma once
// The deferred baseline (issue 2): per view a G-buffer (albedo, normal,
// depth) and a lighting pass (mvr/views/deferred_pipeline.h).
#include <memory>

#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

std::unique_ptr<Renderer> makeDeferredRenderer(const Scene& scene, PixelType type);

}  // namespace mvr
