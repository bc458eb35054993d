#pragma once
// The part of a scene a source's finer outline needs (source_layers.h).
// A slicer reads a pixel's outline only where the pixel is covered and its
// neighbour on the scanline is empty (LayerSlicer::outlineEnd and the GPU
// slicer's), and that outline is made from the samples between the two
// neighbours' centres. Only the triangles that reach those samples need
// the finer pass: on llvmpipe a pass costs per triangle, whatever the
// pixels (the 143K teacup at 640x480, 8 samples: 35 ms a source).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/scene.h"

namespace mvr {

// Whether a slicer reads the outline of pixel i of a row of the nearest
// layer's depths toward dir (-1 left, +1 right): where its neighbour that
// way lies in the image and is empty (LayerSlicer::outlineEnd; the GPU
// slicer's GLSL copy is held to it by GpuImageSlicerTest).
inline bool outlineRead(const float* depthRow, int width, int i, int dir) {
  const int next = i + dir;
  return next >= 0 && next < width && depthRow[next] == 0.0f;
}

// Per pixel of a width x height layer (rows as its depth): 1 where its
// outline is read, covered (depth != 0) beside an empty pixel.
std::vector<uint8_t> outlinePixels(const std::vector<float>& depth, int width, int height);

// The indices (three a triangle, in the scene's order, so that the depth
// test meets them as in the whole mesh) of the triangles that may cover a
// sample the outline of a marked pixel is made from: any sample within a
// pixel of it on its scanline, seen through viewProj onto a width x height
// window. Conservative: a triangle whose bounds are in doubt (a corner at
// or behind the eye) is kept, so the finer depth at those samples equals
// the whole mesh's bit for bit.
std::vector<uint32_t> outlineTriangles(const Scene& scene, const glm::dmat4& viewProj, int width, int height,
                                       const std::vector<uint8_t>& marked);

}  // namespace mvr
