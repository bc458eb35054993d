#pragma once
// Halle 5.6's transform to the two extreme views as a compute pass: the
// scene's positions, lit colours and extras go to GPU memory once, and each
// row of views costs one pass over the vertices that writes the endpoint
// records the PST passes pull (GpuVertices) and the y the GPU slicer reads.
// No CPU work per vertex per frame.
//
// The pass does not clip: it serves a camera whose near and far planes
// enclose the whole scene (needsNoClipping), the usual framing; any other
// camera takes transformToExtremes, which clips on the CPU. It computes in
// double and rounds once to float, as ExtremeTransform does, so both give
// the same records to the last bit almost everywhere.
#include <span>

#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"
#include "shading/lighting.h"
#include "slicing/gpu/gpu_vertices.h"

namespace mvr {

class GpuExtremeTransform {
 public:
  // Uploads positions, colours (view independent: lit once) and extras
  // (extraCount per vertex), and the triangles with their materials and
  // culling. Needs a current GL context.
  GpuExtremeTransform(const Scene& scene, const shading::VertexColors& colors, std::span<const float> extras,
                      int extraCount);

  // The same scene moved in place (mvr/scene_pose.h: new positions and
  // lit colours, the same vertices and triangles): those two uploaded
  // again into the buffers they had; program and triangles stay.
  void moved(const Scene& scene, const shading::VertexColors& colors, std::span<const float> extras);

  // Whether every vertex lies between cam's near and far planes.
  static bool needsNoClipping(const Bounds& sceneBounds, const ShearingCamera& cam);

  // The records of row `row`'s extreme views, rewritten in place: the
  // vertices stay valid until the next call.
  const GpuVertices& transform(const ShearingCamera& cam, int row);
  GLuint yBuffer() const { return y_.id(); }  // per vertex, the row's scanline y

 private:
  gl::Program program_;
  gl::Buffer positions_, shading_, y_;
  GpuVertices vertices_;
  int extraCount_;
};

}  // namespace mvr
