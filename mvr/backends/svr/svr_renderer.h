#pragma once
// The conventional renderers MVR is measured against (issue 2):
//  svr          one draw per view, per-vertex lighting in the vertex shader
//  svr-layered  many views per draw: instancing + gl_Layer into an array;
//               on a GL that renders on the CPU, per-view svr unless
//               layers are forced (tests of the layered path)
#include <memory>

#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

std::unique_ptr<Renderer> makeSvrRenderer(const Scene& scene, PixelType type);
std::unique_ptr<Renderer> makeLayeredSvrRenderer(const Scene& scene, PixelType type,
                                                 bool forceLayers = false);

}  // namespace mvr
