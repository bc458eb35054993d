#pragma once
// PSTs built on the GPU (Halle 5.6.3, 6.4.3): the quad, strip and exact
// geometry of epi/gpu/gl_rasterizer.cpp without a PST vertex made or
// uploaded by the CPU. Per batch of scanlines a compute pass reads the
// batch's slices from the GPU slice table and works out each slice's PST
// pieces (the split at the edge-on view r*, back-face culling) and, in
// strip mode, each piece's sliver count from its twist; a prefix sum turns
// the vertex counts into each slice's first vertex and their total into an
// indirect draw. The passes' vertex shaders pull their vertices by
// gl_VertexID (glslPull): the slice by a binary search over the first
// vertices, then piece, sliver and corner, the endpoints from the extreme
// vertices. Every shading pass draws the same geometry.
//
// Vertices: 6 per sliver (two triangles sharing the diagonal the CPU's
// strips use), K slivers per piece (K = 1 in quad and exact mode).
//
// Texture vectors: slices of the image-based back end carry their own
// (GpuVertices::vectors, per "triangle"); a textured scene's are
// extracted per batch after the count pass (epi/gpu/scene_vectors.h).
#include <optional>
#include <string>

#include "epi/epi_rasterizer.h"
#include "epi/gpu/scene_vectors.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/gl/prefix_sum.h"
#include "shading/gpu_materials.h"
#include "slicing/gpu/gpu_slice_table.h"
#include "slicing/gpu/gpu_vertices.h"

namespace mvr {

// What extracting a textured scene's vectors needs: the extra index of
// u (ShadingPlan::uv), the textures and their GL form (uploaded).
struct SceneTexturing {
  int uv;
  const shading::TextureSet& textures;
  const shading::GpuMaterials& materials;
};

class PstGeometry {
 public:
  // Storage-buffer bindings the pulling vertex shaders read (the Materials
  // block of the shading passes is binding 1), and the texture unit of the
  // vector texels (EpiPass::kVectorUnit; the scene's textures are on
  // TextureSet's units).
  static constexpr GLuint kRecords = 2, kTriangles = 3, kSlices = 4, kOffsets = 5, kFirstVertex = 6,
                          kPieces = 7, kVectors = 8, kVectorUnit = 3;

  // extraCount: the extras per vertex (ExtremeVertices::extraCount);
  // texturing: extract the scene's texture vectors per batch (it must
  // outlive this). Needs a current GL context.
  PstGeometry(PstMode mode, int extraCount, const SceneTexturing* texturing = nullptr);

  // The geometry of scanlines [first, first + count) of `table` for
  // `views` views; vertices and slice table stay on the GPU and must
  // outlive the draws.
  void build(const GpuVertices& vertices, const GpuSliceTable& table, int first, int count, int views);
  // Binds the buffers and sets the pulling uniforms of a pass's program:
  // EPI row coordinate 0 of batch scanline k lies at framebuffer row
  // k chunkRows - view0.
  // With vectors, also their buffer and texels (kVectors, kVectorUnit).
  void bind(const gl::Program& program, int chunkRows, int view0) const;
  void draw() const;  // one indirect draw of the batch
  size_t vectorTexels() const;  // extracted for the last batch

  // GLSL: the slice table and endpoint records: sliceEnds(), End,
  // float endAttribute(End e, int at) reading the record at `at`, and the
  // batch uniforms.
  static std::string glslLibrary(int recordStride);
  // GLSL for a vertex shader: the library, PstVertex pullPstVertex() and
  // uvec4 sliceVector(PstVertex) (a SliceVector: base, length, u0 and u1
  // bits), from the scene's vectors or the slices' own.
  static std::string glslPull(int recordStride, bool sceneVectors);

 private:
  void setSliceUniforms(const gl::Program& p) const;
  void bindBuffers() const;
  void bindVectors() const;
  void viewTexels(const GpuVertices& v);  // texels_ over v's texel buffer

  PstMode mode_;
  gl::Program count_;
  gl::PrefixSum prefixSum_;
  gl::Buffer firstVertex_, pieces_, indirect_;
  gl::VertexArray vao_;  // empty: vertices are pulled
  const GpuVertices* vertices_ = nullptr;
  const GpuSliceTable* table_ = nullptr;
  gl::Texture texels_;  // buffer texture over vertices_->texelBuffer
  std::optional<SceneVectors> sceneVectors_;
  const shading::GpuMaterials* materials_ = nullptr;  // with sceneVectors_
  size_t capacity_ = 0;  // slices the per-slice buffers hold
  uint32_t firstSlice_ = 0, sliceCount_ = 0;
  int views_ = 1, recordStride_;
};

}  // namespace mvr
