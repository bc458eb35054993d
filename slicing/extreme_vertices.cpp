#include "slicing/extreme_vertices.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>

#include "mvr/error.h"

namespace mvr {
namespace {

// A vertex during clipping: world position and the two lit colours, all
// linear in 3D, so clipping may interpolate them directly.
struct ClipVertex {
  glm::dvec3 p;
  glm::vec3 front, back;
  std::array<float, shading::kMaxExtras> extras;
};

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, double t) {
  ClipVertex c{a.p + (b.p - a.p) * t, glm::mix(a.front, b.front, float(t)),
               glm::mix(a.back, b.back, float(t)), {}};
  for (size_t k = 0; k < c.extras.size(); ++k)
    c.extras[k] = a.extras[k] + (b.extras[k] - a.extras[k]) * float(t);
  return c;
}

// Sutherland-Hodgman against one plane: keep where sign * (D - Z - limit) >= 0.
int clipPolygon(const ClipVertex* in, int n, ClipVertex* out, double D, double limit, double sign) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ClipVertex &a = in[i], &b = in[(i + 1) % n];
    const double da = sign * (D - a.p.z - limit), db = sign * (D - b.p.z - limit);
    if (da >= 0) out[m++] = a;
    if ((da >= 0) != (db >= 0)) out[m++] = lerp(a, b, da / (da - db));
  }
  return m;
}

}  // namespace

ExtremeTransform::ExtremeTransform(const ShearingCamera& cam, int row, ExtremeVertices& out)
    : cam_(cam), out_(out) {
  const CameraSpec& s = cam.spec();
  D_ = s.distance;
  n_ = s.nearDistance;
  f_ = s.farDistance;
  sx_ = 2.0 / cam.planeWidth();
  sy_ = 2.0 / cam.planeHeight();
  cxLeft_ = cam.viewX(0);
  cxRight_ = cam.viewX(cam.views() - 1);
  cy_ = cam.rowY(row);
  firstRow_ = row;
  rowStep_ = cam.rows() > 1 ? cam.rowY(1) - cam.rowY(0) : 0.0;
}

void ExtremeTransform::add(const glm::dvec3& p, const glm::vec3& front, const glm::vec3& back,
                           const float* extras) {
  const double w = D_ - p.z;
  const double xl = (sx_ * (D_ * p.x - cxLeft_ * p.z) / w + 1.0) * 0.5 * cam_.width();
  const double xr = (sx_ * (D_ * p.x - cxRight_ * p.z) / w + 1.0) * 0.5 * cam_.width();
  const double y = (-sy_ * (D_ * p.y - cy_ * p.z) / w + 1.0) * 0.5 * cam_.height();
  out_.x0.push_back(float(xl));
  out_.dx.push_back(cam_.views() > 1 ? float((xr - xl) / (cam_.views() - 1)) : 0.0f);
  out_.y.push_back(float(y));
  // dy/dcy = (H / Hp) Z / w: pixels per unit of camera y; y of row 0 is
  // recovered exactly from this row's y.
  const double step = cam_.height() / cam_.planeHeight() * p.z / w * rowStep_;
  out_.yStep.push_back(float(step));
  out_.yFirst.push_back(float(y - firstRow_ * step));
  out_.depth.push_back(float(n_ * (f_ - w) / ((f_ - n_) * w)));
  out_.invW.push_back(float(1.0 / w));
  out_.frontOverW.push_back(front * float(1.0 / w));
  out_.backOverW.push_back(back * float(1.0 / w));
  for (int k = 0; k < out_.extraCount; ++k) out_.extrasOverW.push_back(extras[k] * float(1.0 / w));
}

void ExtremeTransform::skip() {
  for (auto* a : {&out_.x0, &out_.dx, &out_.y, &out_.depth, &out_.invW, &out_.yFirst, &out_.yStep})
    a->push_back(0.0f);
  out_.frontOverW.emplace_back(0.0f);
  out_.backOverW.emplace_back(0.0f);
  out_.extrasOverW.insert(out_.extrasOverW.end(), size_t(out_.extraCount), 0.0f);
}

TriangleRuns TriangleRuns::of(const Scene& scene) {
  TriangleRuns runs;
  const size_t n = scene.triangleCount();
  std::vector<float> centreY(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::uvec3 t = scene.triangles[i];
    centreY[i] = scene.positions[t.x].y + scene.positions[t.y].y + scene.positions[t.z].y;
  }
  runs.order.resize(n);
  std::iota(runs.order.begin(), runs.order.end(), 0u);
  std::stable_sort(runs.order.begin(), runs.order.end(), [&](uint32_t a, uint32_t b) { return centreY[a] < centreY[b]; });
  runs.bounds.resize((n + kSize - 1) / kSize);
  for (size_t r = 0; r < runs.bounds.size(); ++r) {
    Bounds& b = runs.bounds[r] = Bounds::none();
    for (size_t i = r * kSize; i < std::min(n, (r + 1) * kSize); ++i)
      for (int k = 0; k < 3; ++k) b.include(scene.positions[scene.triangles[runs.order[i]][k]]);
  }
  return runs;
}

std::vector<uint8_t> TriangleRuns::keptTriangles(const ShearingCamera& camera) const {
  const IndexRange band = camera.share().scanlines, rows = camera.share().rows;
  if (band.begin <= 0 && band.end >= camera.height()) return {};
  const double D = camera.spec().distance;
  // Scanline centres j + 0.5 of the band, widened by a pixel against rounding.
  const double top = band.begin + 0.5 - 1.0, bottom = band.end - 0.5 + 1.0;
  std::vector<uint8_t> kept(order.size(), 0);
  for (size_t r = 0; r < bounds.size(); ++r) {
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    bool inFront = true;
    for (int corner = 0; corner < 4 && inFront; ++corner) {  // y needs only Y and Z
      const double Y = (corner & 1) ? bounds[r].max.y : bounds[r].min.y;
      const double Z = (corner & 2) ? bounds[r].max.z : bounds[r].min.z;
      inFront = D - Z > 0.0;
      for (int row : {rows.begin, rows.end - 1}) {
        const double y = camera.project({0.0, Y, Z}, 0, row).y;
        lo = std::min(lo, y), hi = std::max(hi, y);
      }
    }
    if (inFront && (hi < top || lo > bottom)) continue;
    for (size_t i = r * kSize; i < std::min(order.size(), (r + 1) * kSize); ++i) kept[order[i]] = 1;
  }
  return kept;
}

void ExtremeVertices::reserve(size_t vertices, size_t triangleCount, size_t texels) {
  for (auto* a : {&x0, &dx, &y, &depth, &invW, &yFirst, &yStep}) a->reserve(vertices);
  frontOverW.reserve(vertices), backOverW.reserve(vertices);
  extrasOverW.reserve(vertices * size_t(extraCount));
  triangles.reserve(triangleCount);
  if (texels > 0) vectors.reserve(triangleCount), vectorTexels.reserve(texels);
}

void appendVertices(ExtremeVertices& to, const ExtremeVertices& from) {
  if (to.extraCount != from.extraCount) fail("appendVertices", "the vertices carry different extras");
  const auto join = [](auto& a, const auto& b) { a.insert(a.end(), b.begin(), b.end()); };
  const auto vertexBase = uint32_t(to.vertexCount());
  const int texelBase = to.vectorTexels.append(from.vectorTexels);
  const int knotBase = int(to.knots.size());
  join(to.x0, from.x0), join(to.dx, from.dx), join(to.y, from.y), join(to.depth, from.depth);
  join(to.invW, from.invW), join(to.yFirst, from.yFirst), join(to.yStep, from.yStep);
  join(to.frontOverW, from.frontOverW), join(to.backOverW, from.backOverW), join(to.extrasOverW, from.extrasOverW);
  for (const glm::uvec3& t : from.triangles) to.triangles.push_back(t + vertexBase);
  join(to.cullBack, from.cullBack), join(to.materials, from.materials), join(to.knots, from.knots);
  for (SliceVector v : from.vectors) {
    v.base += texelBase;
    v.firstKnot += knotBase;
    to.vectors.push_back(v);
  }
}

void moveToRow(ExtremeVertices& v, int row) {
  const float r = float(row);
  for (size_t i = 0; i < v.y.size(); ++i) v.y[i] = v.yFirst[i] + r * v.yStep[i];
}

size_t ExtremeVertices::bytes() const {
  return x0.size() * (7 * sizeof(float) + 2 * sizeof(glm::vec3)) +
         extrasOverW.size() * sizeof(float) + triangles.size() * (sizeof(glm::uvec3) + 5) +
         vectors.size() * sizeof(SliceVector) + vectorTexels.texels().size() * sizeof(glm::vec4) +
         knots.size() * sizeof(HighlightKnot);
}

ExtremeVertices transformToExtremes(const Scene& scene, const shading::VertexColors& colors,
                                    const ShearingCamera& camera, int row,
                                    std::span<const float> extras, int extraCount, const TriangleRuns* runs) {
  if (extraCount > shading::kMaxExtras || extras.size() != scene.vertexCount() * size_t(extraCount))
    fail("transformToExtremes", "extras do not match the scene's vertices");
  if (runs && runs->order.size() != scene.triangleCount())
    fail("transformToExtremes", "triangle runs are not the scene's");
  // Triangles of runs that cannot reach the share are dropped, and with
  // them the vertices only they use.
  const std::vector<uint8_t> reach = runs ? runs->keptTriangles(camera) : std::vector<uint8_t>{};
  const auto kept = [&](size_t triangle) { return reach.empty() || reach[triangle]; };
  const size_t nv = scene.vertexCount();
  std::vector<uint8_t> needed(nv, reach.empty() ? 1 : 0);
  if (!reach.empty())
    for (size_t i = 0; i < scene.triangleCount(); ++i)
      if (kept(i)) needed[scene.triangles[i].x] = needed[scene.triangles[i].y] = needed[scene.triangles[i].z] = 1;
  ExtremeVertices out;
  out.extraCount = extraCount;
  out.extrasOverW.reserve(extras.size());
  ExtremeTransform t(camera, row, out);
  for (auto* v : {&out.x0, &out.dx, &out.y, &out.depth, &out.invW, &out.yFirst, &out.yStep})
    v->reserve(nv);
  std::vector<uint8_t> inside(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (!needed[v]) {
      t.skip();
      continue;
    }
    const glm::dvec3 p(scene.positions[v]);
    inside[v] = t.inside(p);
    // Vertices outside near/far still get a slot so indices stay valid;
    // only triangles that are wholly inside use them unclipped.
    glm::dvec3 safe = inside[v] ? p : glm::dvec3(p.x, p.y, t.D() - t.nearDistance());
    t.add(safe, colors.front[v], colors.back[v], extras.data() + v * extraCount);
  }
  out.triangles.reserve(scene.triangleCount());
  out.cullBack.reserve(scene.triangleCount());
  out.materials.reserve(scene.triangleCount());
  for (size_t i = 0; i < scene.triangleCount(); ++i) {
    if (!kept(i)) continue;
    const glm::uvec3 tri = scene.triangles[i];
    const uint8_t cull = scene.materials[scene.materialIds[i]].twoSided ? 0 : 1;
    if (inside[tri.x] && inside[tri.y] && inside[tri.z]) {
      out.triangles.push_back(tri);
      out.cullBack.push_back(cull);
      out.materials.push_back(scene.materialIds[i]);
      continue;
    }
    std::array<ClipVertex, 5> a, b;
    for (int k = 0; k < 3; ++k) {
      a[k] = {glm::dvec3(scene.positions[tri[k]]), colors.front[tri[k]], colors.back[tri[k]], {}};
      std::copy_n(extras.data() + tri[k] * size_t(extraCount), extraCount, a[k].extras.begin());
    }
    int n = clipPolygon(a.data(), 3, b.data(), t.D(), t.nearDistance(), +1.0);
    n = clipPolygon(b.data(), n, a.data(), t.D(), t.farDistance(), -1.0);
    if (n < 3) continue;
    const auto base = unsigned(out.vertexCount());
    for (int k = 0; k < n; ++k) t.add(a[k].p, a[k].front, a[k].back, a[k].extras.data());
    for (int k = 1; k + 1 < n; ++k) {  // fan keeps the winding
      out.triangles.push_back({base, base + k, base + k + 1});
      out.cullBack.push_back(cull);
      out.materials.push_back(scene.materialIds[i]);
    }
  }
  return out;
}

}  // namespace mvr
