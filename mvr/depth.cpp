#include "mvr/depth.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "mvr/error.h"

namespace mvr {

Scene depthScene(const Scene& scene, const ShearingCamera& cam, DepthColoring& coloring) {
  Scene out;
  out.positions = scene.positions;
  out.normals = scene.normals;
  out.uvs = scene.uvs;
  out.triangles = scene.triangles;
  out.materialIds = scene.materialIds;
  out.source = scene.source;
  out.camera = scene.camera;
  out.ambient = glm::vec3(1.0f);
  out.exactColors = true;
  for (const Material& m : scene.materials) {
    Material matte;
    matte.name = m.name;
    matte.diffuse = glm::vec3(1.0f);
    matte.twoSided = m.twoSided;
    if (m.masked()) {  // its cut-out's alpha only (TextureSet: exact colours)
      matte.texture = m.texture;
      matte.textureImage = m.textureImage;
      matte.alphaCutoff = m.alphaCutoff;
    }
    out.materials.push_back(matte);
  }
  const glm::dmat4 v = cam.worldToCamera(0, 0);
  std::vector<double> depth(scene.vertexCount());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t i = 0; i < depth.size(); ++i) {
    depth[i] = (v * glm::dvec4(glm::dvec3(scene.positions[i]), 1.0)).z;
    lo = std::min(lo, depth[i]);
    hi = std::max(hi, depth[i]);
  }
  coloring = DepthColoring{depth.empty() ? 0.0 : lo, hi > lo ? hi - lo : 1.0};
  out.colors.resize(depth.size());
  for (size_t i = 0; i < depth.size(); ++i) out.colors[i] = glm::vec3(coloring.colorOf(depth[i]));
  return out;
}

namespace {

void depthsOf(const Image& frame, const DepthColoring& coloring, float* depth) {
  if (frame.type != PixelType::F32) fail("depth", "the depth scene must be rendered in float");
  const float* px = reinterpret_cast<const float*>(frame.bytes.data());
  const size_t n = size_t(frame.width) * frame.height;
  for (size_t i = 0; i < n; ++i) depth[i] = px[4 * i + 3] > 0.5f ? coloring.depthOf(px[4 * i]) : 0.0f;
}

}  // namespace

DepthImage depthFromColors(const Image& view, const DepthColoring& coloring) {
  DepthImage depth(view.width, view.height);
  depthsOf(view, coloring, depth.values.data());
  return depth;
}

void packDepth(const Image& frame, const DepthColoring& coloring, Image& packed) {
  static_assert(sizeof(float) == 4, "a packed pixel (4 bytes) is one float");
  if (packed.width != frame.width || packed.height != frame.height || packed.type != kPackedDepth)
    packed = Image(frame.width, frame.height, kPackedDepth);
  depthsOf(frame, coloring, reinterpret_cast<float*>(packed.bytes.data()));
}

DepthImage unpackDepth(const Image& packed) {
  if (packed.type != kPackedDepth) fail("depth", "a packed depth map holds 4 bytes a pixel");
  DepthImage depth(packed.width, packed.height);
  std::memcpy(depth.values.data(), packed.bytes.data(), depth.values.size() * sizeof(float));
  return depth;
}

}  // namespace mvr
