#pragma once
// Polygon slice tracks (Halle 5.6.3, 6.4.3). In the EPI of a scanline (x
// across, view down) a slice sweeps a quadrilateral: its endpoints are
// fixed 3D points, so their tracks are straight lines. Rows are sampled at
// r = i + 0.5 for view i; the corners are extrapolated to r = 0 and r = N
// so that fill rules never drop the first or last view.
//
// Corners: (x0L, 0), (x1L, 0), (x0R, N), (x1R, N); widths dL = x1L - x0L,
// dR = x1R - x0R. When dL dR < 0 the i-edges cross at r* = N dL / (dL - dR)
// (the edge-on view): the two pieces face opposite ways.
//
// Inside a PST the screen-space slice parameter of pixel (x, r) is
// u = (x - x0(r)) / (x1(r) - x0(r)): the same for every view, because w does
// not depend on the view. Attributes are hyperbolic in u; depth is linear.
#include <array>

#include "slicing/slice_table.h"

namespace mvr {

struct PstPiece {
  float rTop, rBottom;  // EPI row coordinates, rTop < rBottom
  bool front;           // x1 - x0 > 0 inside this piece
};

struct Pst {
  SliceEnd e0, e1;
  int pieceCount = 0;
  std::array<PstPiece, 2> pieces{};

  float x0(float r) const { return e0.x0 + (r - 0.5f) * e0.dx; }
  float x1(float r) const { return e1.x0 + (r - 0.5f) * e1.dx; }
  float width(float r) const { return x1(r) - x0(r); }
};

// views = N >= 1. Pieces facing away are dropped when cullBack is set.
Pst makePst(const SliceEnd& e0, const SliceEnd& e1, int views, bool cullBack);

// The colour of the slice at screen parameter u in [0, 1]: hyperbolic
// interpolation of colour / w, divided by the interpolated 1 / w.
// Inline: the CPU span back end calls both for every pixel it fills.
inline glm::vec3 pstColor(const Pst& pst, bool front, float u) {
  const glm::vec3 c0 = front ? pst.e0.frontOverW : pst.e0.backOverW;
  const glm::vec3 c1 = front ? pst.e1.frontOverW : pst.e1.backOverW;
  const float invW = pst.e0.invW + (pst.e1.invW - pst.e0.invW) * u;
  return (c0 + (c1 - c0) * u) / invW;
}
inline float pstDepth(const Pst& pst, float u) { return pst.e0.depth + (pst.e1.depth - pst.e0.depth) * u; }

// N of the slice's extra attributes from index `at`, at screen parameter u:
// hyperbolic, as pstColor.
inline void pstExtras(const Pst& pst, int at, int count, float u, float* out) {
  const float invW = pst.e0.invW + (pst.e1.invW - pst.e0.invW) * u;
  for (int c = 0; c < count; ++c) {
    const float a = pst.e0.extrasOverW[at + c], b = pst.e1.extrasOverW[at + c];
    out[c] = (a + (b - a) * u) / invW;
  }
}
template <int N>
glm::vec<N, float> pstExtras(const Pst& pst, int at, float u) {
  glm::vec<N, float> v;
  pstExtras(pst, at, N, u, &v[0]);
  return v;
}

}  // namespace mvr
