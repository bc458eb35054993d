#pragma once
// The texture vectors of a batch's slices (shading/texture_vector.h)
// extracted on the GPU, for the pulled PSTs of epi/gpu/pst_geometry.h: the
// same vectors TextureVectors::add makes on the CPU, without a slice
// visiting the host. Three compute passes after PstGeometry's count pass:
//   size    per slice its level-0 length K (the wider p-edge of its drawn
//           pieces, in pixels, rounded up to a power of two; 0 for a
//           culled slice or an untextured material) and its 2K - 1
//           texels (twice that where the material's emission has a
//           texture: its chain follows), scanned by a prefix sum into
//           first texels;
//   sample  per level-0 texel the perspective-correct uv at its centre,
//           sampled from the scene's texture array at the level of its
//           footprint (as TextureSet::sample, by the GL's sampler);
//   levels  per slice its box-filtered MIP chain, in the CPU's order.
// The texel total comes back to size the texel buffer: one small read per
// batch, the only sync of the pass.
#include <cstdint>
#include <string>

#include "mvr/gl/gl_handles.h"
#include "mvr/gl/prefix_sum.h"
#include "shading/gpu_materials.h"
#include "shading/texture_set.h"

namespace mvr {

class SceneVectors {
 public:
  // Storage bindings: per slice of the batch its first texel and level-0
  // length (what the pulling vertex shaders read), and the texels while
  // they are written.
  static constexpr GLuint kBase = 8, kLength = 9, kTexels = 10;

  // pstLibrary: PstGeometry::glslLibrary, the slice table and endpoint
  // records its passes read; uvAt: the record index of u / w (v / w
  // follows). Needs a current GL context.
  SceneVectors(const std::string& pstLibrary, int uvAt, const shading::TextureSet& textures);

  // The batch's slices [firstSlice, firstSlice + sliceCount), their pieces
  // written by PstGeometry's count pass. Expects PstGeometry's storage
  // buffers (records, triangles, slices, pieces) bound; binds materials
  // (the Materials block and the texture groups) before each pass, as the
  // prefix sum between them takes binding 1.
  void build(uint32_t firstSlice, uint32_t sliceCount, int views, const shading::GpuMaterials& materials);
  // Binds the per-slice buffers and the texels' buffer texture at unit
  // `vectorUnit` for the pulling vertex and fragment shaders.
  void bind(GLuint vectorUnit) const;
  size_t texelCount() const { return texelCount_; }

  // GLSL for the pulling vertex shaders: uvec4 sliceVector(uint slice),
  // the SliceVector layout of GpuVertices::vectors for a batch slice.
  static const char* glslPull();

 private:
  void setUniforms(const gl::Program& p) const;
  void reserveSlices(uint32_t count);
  void reserveTexels(size_t count);

  gl::Program size_, sample_, levels_;
  gl::PrefixSum prefixSum_;
  gl::Buffer base_, length_, total_, texels_;
  gl::Texture texelTexture_;  // buffer texture over texels_
  size_t sliceCapacity_ = 0, texelCapacity_ = 0, texelCount_ = 0;
  uint32_t firstSlice_ = 0, sliceCount_ = 0;
  int views_ = 1;
};

}  // namespace mvr
