#include "slicing/slice_table.h"

#include <algorithm>
#include <cmath>

#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {

std::pair<int, int> scanlineRange(float y0, float y1, float y2, int height) {
  const float lo = std::min({y0, y1, y2}), hi = std::max({y0, y1, y2});
  // First j with j + 0.5 >= lo; first j with j + 0.5 >= hi ends the range.
  const int first = std::max(0, int(std::ceil(lo - 0.5f)));
  const int last = std::min(height, int(std::ceil(hi - 0.5f)));
  return {first, std::max(first, last)};
}

namespace {

struct Sorted {
  int a, b, c;
  bool swap;  // permutation parity decides the endpoint order
};

// Sorts the corners by y. For window coordinates with y down, a triangle
// facing the camera has negative signed area; the short-edge endpoint lies
// right of the long-edge one exactly when the sorted triangle's area is
// positive, which flips with the permutation's parity (derivation in
// docs/ARCHITECTURE.md, "slice orientation").
Sorted sortByY(const ExtremeVertices& v, const glm::uvec3& t) {
  int idx[3] = {0, 1, 2};
  bool odd = false;
  auto y = [&](int k) { return v.y[t[idx[k]]]; };
  if (y(1) < y(0)) std::swap(idx[0], idx[1]), odd = !odd;
  if (y(2) < y(1)) std::swap(idx[1], idx[2]), odd = !odd;
  if (y(1) < y(0)) std::swap(idx[0], idx[1]), odd = !odd;
  // Even permutation: endpoints (short, long); odd: (long, short).
  return {idx[0], idx[1], idx[2], !odd};
}

template <class Emit>
void sliceTriangle(const ExtremeVertices& v, uint32_t tri, int bandLo, int bandHi, Emit&& emit) {
  const glm::uvec3 t = v.triangles[tri];
  auto [first, last] = scanlineRange(v.y[t.x], v.y[t.y], v.y[t.z], bandHi);
  first = std::max(first, bandLo);
  if (first >= last) return;
  const Sorted s = sortByY(v, t);
  const float ya = v.y[t[s.a]], yb = v.y[t[s.b]], yc = v.y[t[s.c]];
  const uint32_t corners = uint32_t(s.a) | uint32_t(s.b) << 2 | uint32_t(s.c) << 4;
  for (int j = first; j < last; ++j) {
    const float y = j + 0.5f;
    const bool lower = y >= yb;
    // Every edge p -> q (y_p <= y_q) in one form, (y - y_p) / (y_q - y_p):
    // the triangles that share an edge, where it is long in one and short
    // in the other, put their ends at the same float, so that no pixel
    // centre on the seam falls between them (a reciprocal of the long
    // edge's rounded differently and left such cracks).
    const float tLong = (y - ya) / (yc - ya);
    const float tShort = lower ? (y - yb) / (yc - yb) : (y - ya) / (yb - ya);
    const uint32_t flags = corners | (lower ? 1u << 6 : 0u) | (s.swap ? 1u << 7 : 0u);
    emit(j, Slice{tri, tLong, tShort, flags});
  }
}

}  // namespace

SliceTable SliceTable::build(const ExtremeVertices& v, int height, int bands) {
  return build(v, height, IndexRange{0, height}, bands);
}

SliceTable SliceTable::build(const ExtremeVertices& v, int height, IndexRange scanlines, int bands) {
  if (scanlines.begin < 0 || scanlines.end > height || scanlines.size() < 0)
    fail("slice table", "scanlines outside the image");
  const int lines = scanlines.size();
  if (bands <= 0) bands = threadCount();
  bands = std::clamp(bands, 1, std::max(1, lines));
  SliceTable table;
  table.offsets_.assign(height + 1, 0);
  const auto triangles = uint32_t(v.triangles.size());
  auto band = [&](int k) {
    return std::pair{scanlines.begin + lines * k / bands, scanlines.begin + lines * (k + 1) / bands};
  };
  // Pass 1: count per scanline (each task writes only its own band).
  parallelFor(0, bands, [&](int k) {
    auto [lo, hi] = band(k);
    for (uint32_t tri = 0; tri < triangles; ++tri)
      sliceTriangle(v, tri, lo, hi, [&](int j, const Slice&) { ++table.offsets_[j + 1]; });
  });
  for (int j = 0; j < height; ++j) table.offsets_[j + 1] += table.offsets_[j];
  table.slices_.resize(table.offsets_[height]);
  // Pass 2: fill, in triangle order within each scanline.
  parallelFor(0, bands, [&](int k) {
    auto [lo, hi] = band(k);
    std::vector<uint32_t> cursor(table.offsets_.begin() + lo, table.offsets_.begin() + hi);
    for (uint32_t tri = 0; tri < triangles; ++tri)
      sliceTriangle(v, tri, lo, hi,
                    [&](int j, const Slice& s) { table.slices_[cursor[j - lo]++] = s; });
  });
  return table;
}

SliceTable SliceTable::fromArrays(std::vector<uint32_t> offsets, std::vector<Slice> slices) {
  bool ok = !offsets.empty() && offsets.front() == 0 && offsets.back() == slices.size();
  for (size_t j = 1; ok && j < offsets.size(); ++j) ok = offsets[j - 1] <= offsets[j];
  if (!ok) fail("slice table", "offsets are not prefix sums of the slices");
  SliceTable table;
  table.offsets_ = std::move(offsets);
  table.slices_ = std::move(slices);
  return table;
}

SliceTable SliceTable::fromSegments(const std::vector<uint32_t>& scanlineOf, int height) {
  SliceTable table;
  table.offsets_.assign(height + 1, 0);
  for (uint32_t j : scanlineOf) ++table.offsets_[j + 1];
  for (int j = 0; j < height; ++j) table.offsets_[j + 1] += table.offsets_[j];
  table.slices_.resize(scanlineOf.size());
  std::vector<uint32_t> cursor(table.offsets_.begin(), table.offsets_.end() - 1);
  for (uint32_t k = 0; k < scanlineOf.size(); ++k)
    table.slices_[cursor[scanlineOf[k]]++] = Slice{k, 0.0f, 0.0f, kSegmentSlice};
  return table;
}

namespace {

SliceEnd endAt(const ExtremeVertices& v, uint32_t p, uint32_t q, float t) {
  auto mix = [t](float a, float b) { return a + (b - a) * t; };
  // Default-initialised: only the first extraCount extras are written or
  // read, and zeroing the rest costs on the hottest path of diffuse scenes.
  SliceEnd e;
  e.x0 = mix(v.x0[p], v.x0[q]);
  e.dx = mix(v.dx[p], v.dx[q]);
  e.depth = mix(v.depth[p], v.depth[q]);
  e.invW = mix(v.invW[p], v.invW[q]);
  e.frontOverW = glm::mix(v.frontOverW[p], v.frontOverW[q], t);
  e.backOverW = glm::mix(v.backOverW[p], v.backOverW[q], t);
  const int k = v.extraCount;
  const float *ep = v.extrasOverW.data() + size_t(p) * k, *eq = v.extrasOverW.data() + size_t(q) * k;
  for (int c = 0; c < k; ++c) e.extrasOverW[c] = mix(ep[c], eq[c]);
  return e;
}

}  // namespace

std::pair<SliceEnd, SliceEnd> sliceEnds(const ExtremeVertices& v, const Slice& s) {
  const glm::uvec3 t = v.triangles[s.triangle];
  if (s.flags & kSegmentSlice) return {endAt(v, t.x, t.x, 0.0f), endAt(v, t.y, t.y, 0.0f)};
  const uint32_t a = t[s.flags & 3], b = t[(s.flags >> 2) & 3], c = t[(s.flags >> 4) & 3];
  const SliceEnd onLong = endAt(v, a, c, s.tLong);
  const SliceEnd onShort = (s.flags & (1u << 6)) ? endAt(v, b, c, s.tShort) : endAt(v, a, b, s.tShort);
  if (s.flags & (1u << 7)) return {onShort, onLong};
  return {onLong, onShort};
}

}  // namespace mvr
