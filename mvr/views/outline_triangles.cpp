#include "mvr/views/outline_triangles.h"

#include <algorithm>
#include <cmath>

#include "mvr/parallel.h"

namespace mvr {
namespace {

// Beyond the snapping of a GL rasterizer (1/256 pixel or finer): a corner
// this near a sample's row or column counts as reaching it.
constexpr double kSlack = 1.0 / 64.0;

// v as an index clamped to [lo, hi] (v may be far outside int's range).
int within(double v, int lo, int hi) { return int(std::clamp(v, double(lo), double(hi))); }

// Runs body(begin, end) over [0, n) in chunks on the pool.
template <class Body>
void inChunks(size_t n, Body&& body) {
  parallelChunks(n, 4096, body);
}

// Per row, the count of pixels before each column whose samples an
// outline reads: a marked pixel and its two neighbours on the scanline.
struct Reach {
  Reach(const std::vector<uint8_t>& marked, int width, int height)
      : width(width), before(size_t(width + 1) * height, 0) {
    for (int j = 0; j < height; ++j) {
      const uint8_t* m = marked.data() + size_t(j) * width;
      uint32_t* b = before.data() + size_t(j) * (width + 1);
      for (int c = 0; c < width; ++c)
        b[c + 1] = b[c] + ((c > 0 && m[c - 1]) || m[c] || (c + 1 < width && m[c + 1]) ? 1u : 0u);
    }
  }
  bool any(int row, int first, int last) const {
    const uint32_t* b = before.data() + size_t(row) * (width + 1);
    return b[last + 1] > b[first];
  }
  int width;
  std::vector<uint32_t> before;
};

}  // namespace

std::vector<uint8_t> outlinePixels(const std::vector<float>& depth, int width, int height) {
  std::vector<uint8_t> marked(size_t(width) * height, 0);
  for (int j = 0; j < height; ++j) {
    const float* d = depth.data() + size_t(j) * width;
    uint8_t* m = marked.data() + size_t(j) * width;
    for (int i = 0; i < width; ++i)
      m[i] = d[i] != 0.0f && (outlineRead(d, width, i, -1) || outlineRead(d, width, i, +1));
  }
  return marked;
}

std::vector<uint32_t> outlineTriangles(const Scene& scene, const glm::dmat4& viewProj, int width, int height,
                                       const std::vector<uint8_t>& marked) {
  const Reach reach(marked, width, height);
  std::vector<glm::dvec4> clip(scene.vertexCount());
  inChunks(clip.size(), [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) clip[v] = viewProj * glm::dvec4(glm::dvec3(scene.positions[v]), 1.0);
  });
  // A triangle with every corner before the eye projects inside its
  // corners' window bounds, clipped or not; samples lie on pixel centres'
  // rows, at any column.
  const auto reaches = [&](const glm::uvec3& t) {
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec4& c = clip[t[k]];
      if (!(c.w > 0.0)) return true;
      const glm::dvec2 p((c.x / c.w * 0.5 + 0.5) * width, (c.y / c.w * 0.5 + 0.5) * height);
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return true;
      lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    const int firstRow = within(std::ceil(lo.y - 0.5 - kSlack), 0, height);
    const int lastRow = within(std::floor(hi.y - 0.5 + kSlack), -1, height - 1);
    const int first = within(std::floor(lo.x - kSlack), 0, width);
    const int last = within(std::floor(hi.x + kSlack), -1, width - 1);
    for (int j = firstRow; j <= lastRow && first <= last; ++j)
      if (reach.any(j, first, last)) return true;
    return false;
  };
  std::vector<uint8_t> keep(scene.triangleCount(), 0);
  inChunks(keep.size(), [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) keep[t] = reaches(scene.triangles[t]) ? 1 : 0;
  });
  std::vector<uint32_t> indices;
  for (size_t t = 0; t < keep.size(); ++t)
    if (keep[t]) indices.insert(indices.end(), {scene.triangles[t][0], scene.triangles[t][1], scene.triangles[t][2]});
  return indices;
}

}  // namespace mvr
