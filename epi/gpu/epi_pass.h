#pragma once
// One GL shading pass over PST geometry (Halle 6.5: multi-pass shading).
// Every pass draws the same PST geometry with the same depth; passes after
// the first test depth EQUAL and blend into the float target: the texture
// pass multiplies, the view-dependent pass adds. A scene with cut-outs
// (ShadingPlan::mask) first runs the texture pass as a depth pass that
// discards the cut texels; the diffuse pass then tests EQUAL too.
//
// Each pass needs a few attributes per slice endpoint (divided by w). The
// vertex layouts (floats):
//   quad, strip  x, y, depth, view | side, material, 0, 0 | attributes at
//                the vertex, divided back (linear across slivers)
//   exact        x, y, num, den | depth0, depth1, 1/w0, 1/w1 | view, side,
//                material, 0 | attributes/w at end 0 | at end 1
// `view` is the EPI row coordinate minus one half (view i at view = i), for
// the eye of the view-dependent pass; `side` is +1 front, -1 back.
#include "epi/epi_rasterizer.h"
#include "mvr/gl/gl_handles.h"

namespace mvr {

class EpiPass {
 public:
  // pulled: the vertex shader pulls PST vertices from the GPU slice table
  // (PstGeometry) instead of reading the CPU-built layouts below; split
  // highlight tracks (image slices' knots) are not pulled.
  // maskDepth: the cut-outs' depth pass (a texture pass writing depth only).
  EpiPass(PstMode mode, shading::Pass pass, const EpiShading& shading, bool pulled = false,
          bool maskDepth = false);

  shading::Pass pass() const { return pass_; }
  int attributeCount() const { return count_; }
  // The texture-vector pass: attributes (u, first texel, length) are linear
  // in screen space and are not divided by w; gather() does not apply. u
  // runs from SliceVector::u0 at end 0 to u1 at end 1 (0 and 1 for the
  // vectors the rasterizer extracts itself). The sliver modes carry u as
  // (u times the slice width, the width, first texel, length).
  bool linear() const;
  // The pass that writes depth (and colour, but for the cut-outs' depth
  // pass); later passes test depth EQUAL and blend (the diffuse pass after
  // a cut-outs' depth pass writes its colour).
  bool first() const;
  // A texture pass that blends by two sources to keep the emission
  // (ShadingPlan::emission).
  bool emission() const;
  int stride() const;  // floats per vertex
  const gl::Program& program() const { return program_; }
  // This pass's attributes of one endpoint, divided by w.
  void gather(const SliceEnd& e, bool front, float* out) const;
  // Uses the program and sets its uniforms and the blend and depth state.
  void begin(const glm::vec2& scale, const glm::vec3& eye0, const glm::vec3& eyeStep) const;
  // The texture unit the vector texture pass reads (the buffer texture of
  // this batch's vectors; direct texturing reads TextureSet's units).
  // Passes after the first also read the Materials storage block, which
  // the caller binds.
  static constexpr GLuint kVectorUnit = 3;
  // Exact mode: how far the GL's sub-pixel snapping may move a PST's edge
  // at a row, per unit of (1 + the edge's slope in pixels per view). Exact
  // quads are widened by it and the fragment keeps only pixel centres in
  // the exact span, as the CPU spans do: over long tracks (slopes of 30 px
  // per view) snapping a vertex's row moved edges by a tenth of a pixel
  // and the depth test then showed the surface behind.
  static float edgeSnap();
  // Binds this pass's vertex array over these vertex and index buffers.
  void bindVertices(GLuint vertices, GLuint indices) const;

 private:
  int chunks() const { return (count_ + 3) / 4; }

  PstMode mode_;
  shading::Pass pass_;
  const EpiShading& shading_;
  bool maskDepth_ = false;
  int count_ = 0;
  gl::Program program_;
  gl::VertexArray vao_;
};

}  // namespace mvr
