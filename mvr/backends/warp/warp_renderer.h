#pragma once
// The depth-image warping back end (seed 003; mvr/backends/warp/depth_warp.h): each
// view composited from its two nearest RGB-D references. References come
// from a scene, rendered by the deferred pipeline at source eyes on the
// track (as interp's sources), or from a capture (mvr synthesize).
#include <memory>
#include <vector>

#include "mvr/backends/warp/warp_options.h"
#include "mvr/renderer.h"
#include "mvr/rgbd_view.h"
#include "mvr/scene.h"

namespace mvr {

// Needs a current GL context.
std::unique_ptr<Renderer> makeWarpRenderer(const Scene& scene, PixelType type, const WarpOptions& options);
// Views of a capture: every reference must have the same size. track: the
// views it will render, if known: where every row of them has references
// on it (each the view of track's camera at its eye on that row, as our
// sets and the HCI layout are), the CPU warp can take them.
std::unique_ptr<Renderer> makeWarpRenderer(std::vector<RgbdView> references, PixelType type,
                                           const WarpOptions& options, const ShearingCamera* track = nullptr);

}  // namespace mvr
