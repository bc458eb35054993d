#pragma once
// The conventional renderers MVR is measured against (issue 2):
//  svr          one draw per view, per-vertex lighting in the vertex shader
//  svr-layered  many views per draw: instancing + gl_Layer into an array
//  deferred     per view a G-buffer (albedo, normal, depth) and a lighting pass
#include <memory>

#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

std::unique_ptr<Renderer> makeSvrRenderer(const Scene& scene, PixelType type);
std::unique_ptr<Renderer> makeLayeredSvrRenderer(const Scene& scene, PixelType type);
std::unique_ptr<Renderer> makeDeferredRenderer(const Scene& scene, PixelType type);

}  // namespace mvr
