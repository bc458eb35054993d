#include "mvr/assets/point_line_solids.h"

#include <algorithm>
#include <cmath>

namespace mvr {
namespace {

class SolidWriter {
 public:
  explicit SolidWriter(Scene& scene) : scene_(scene) {}

  // Octant (sx, sy, sz)'s face, wound outward: the three axis tips, in
  // the order (x, y, z) when the octant's sign product is positive.
  void octahedron(const PointLineSet::Mark& m, float r, uint32_t material) {
    const uint32_t base = uint32_t(scene_.positions.size());
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& a : axes) vertex(m.position + r * a, a, m.color);
    for (int o = 0; o < 8; ++o) {
      const int sx = o & 1, sy = o >> 1 & 1, sz = o >> 2 & 1;  // 0: +, 1: -
      glm::uvec3 t(base + uint32_t(sx), base + 2 + uint32_t(sy), base + 4 + uint32_t(sz));
      if ((sx + sy + sz) % 2) std::swap(t.y, t.z);
      triangle(t, material);
    }
  }

  void prism(const PointLineSet::Mark& a, const PointLineSet::Mark& b, float w, uint32_t material) {
    const glm::vec3 d = b.position - a.position;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return;
    const glm::vec3 u = d / length;
    const glm::vec3 helper = std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 p1 = glm::normalize(glm::cross(u, helper)), p2 = glm::cross(u, p1);
    const glm::vec3 sides[4] = {p1, p2, -p1, -p2};
    const uint32_t base = uint32_t(scene_.positions.size());
    for (const glm::vec3& s : sides) vertex(a.position + w * s, s, a.color);
    for (const glm::vec3& s : sides) vertex(b.position + w * s, s, b.color);
    // Side k: (a_k, a_k+1, b_k+1) and (a_k, b_k+1, b_k); its normal is
    // (o_k+1 - o_k) x u, which points out (p2 = u x p1).
    for (uint32_t k = 0; k < 4; ++k) {
      const uint32_t n = (k + 1) % 4;
      triangle({base + k, base + n, base + 4 + n}, material);
      triangle({base + k, base + 4 + n, base + 4 + k}, material);
    }
  }

 private:
  void vertex(const glm::vec3& p, const glm::vec3& n, const glm::vec3& color) {
    scene_.positions.push_back(p);
    scene_.normals.push_back(n);
    scene_.colors.push_back(color);
    if (!scene_.uvs.empty()) scene_.uvs.emplace_back(0.0f);
  }
  void triangle(const glm::uvec3& t, uint32_t material) {
    scene_.triangles.push_back(t);
    scene_.materialIds.push_back(material);
  }
  Scene& scene_;
};

}  // namespace

void addPointLineSolids(Scene& scene, const PointLineSet& set) {
  if (set.empty()) return;
  Bounds b = Bounds::none();
  for (const glm::vec3& p : scene.positions) b.include(p);
  for (const auto& m : set.points) b.include(m.position);
  for (const auto& [a, c] : set.segments) b.include(a.position), b.include(c.position);
  float diagonal = glm::length(b.max - b.min);
  if (!(diagonal > 0.0f) || !std::isfinite(diagonal)) diagonal = 1.0f;
  const float radius = diagonal * std::min(0.01f, 0.5f / std::sqrt(float(std::max<size_t>(set.points.size(), 1))));
  const float width = diagonal * std::min(0.004f, 0.2f / std::sqrt(float(std::max<size_t>(set.segments.size(), 1))));
  SolidWriter out(scene);
  for (size_t i = 0; i < set.points.size(); ++i) out.octahedron(set.points[i], radius, set.pointMaterials[i]);
  for (size_t i = 0; i < set.segments.size(); ++i)
    out.prism(set.segments[i].first, set.segments[i].second, width, set.segmentMaterials[i]);
}

}  // namespace mvr
