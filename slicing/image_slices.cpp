#include "slicing/image_slices.h"

#include "mvr/error.h"

namespace mvr {

ImageSlices sliceSourceLayers(const std::vector<SourceLayer>& layers, const ShearingCamera& cam,
                              int row, float overlap) {
  ImageSlices out;
  std::vector<uint32_t> scanlineOf;
  ExtremeTransform transform(cam, row, out.vertices);
  const int w = cam.width(), h = cam.height();
  for (const SourceLayer& layer : layers) {
    if (layer.color.width != w || layer.color.height != h || layer.color.type != PixelType::F32)
      fail("sliceSourceLayers", "source layers must be float images of the output size");
    for (int j = 0; j < h; ++j)
      for (int x = 0; x < w; ++x) {
        const float depth = layer.depth[size_t(j) * w + x];
        if (depth == 0.0f) continue;
        const glm::vec3 c(layer.color.pixel(x, j));
        const auto base = uint32_t(out.vertices.vertexCount());
        for (double edge : {double(x) - overlap, x + 1.0 + overlap})
          transform.add(cam.unprojectAt(layer.eye.x, layer.eye.y, {edge, j + 0.5, depth}), c, c, nullptr);
        out.vertices.triangles.push_back({base, base + 1, base + 1});
        scanlineOf.push_back(uint32_t(j));
      }
  }
  out.vertices.cullBack.assign(out.vertices.triangles.size(), 0);
  out.vertices.materials.assign(out.vertices.triangles.size(), 0);
  out.table = SliceTable::fromSegments(scanlineOf, h);
  return out;
}

}  // namespace mvr
