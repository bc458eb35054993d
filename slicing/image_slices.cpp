#include "slicing/image_slices.h"

#include "mvr/error.h"

namespace mvr {

glm::dvec3 unproject(const ShearingCamera& cam, const glm::dvec2& eye, double x, double y,
                     double depth) {
  // Inverse of ShearingCamera::viewProjectionAt: depth = n (f - w) / ((f - n) w).
  const CameraSpec& s = cam.spec();
  const double n = s.nearDistance, f = s.farDistance, D = s.distance;
  const double w = n * f / (depth * (f - n) + n), Z = D - w;
  const double xNdc = 2.0 * x / cam.width() - 1.0, yNdc = 2.0 * y / cam.height() - 1.0;
  const double X = (xNdc * w * cam.planeWidth() / 2.0 + eye.x * Z) / D;
  const double Y = (-yNdc * w * cam.planeHeight() / 2.0 + eye.y * Z) / D;
  return {X, Y, Z};
}

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
        transform.add(unproject(cam, layer.eye, x - overlap, j + 0.5, depth), c, c, nullptr);
        transform.add(unproject(cam, layer.eye, x + 1.0 + overlap, j + 0.5, depth), c, c, nullptr);
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
