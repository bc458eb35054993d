#include "epi/pst.h"

namespace mvr {

Pst makePst(const SliceEnd& e0, const SliceEnd& e1, int views, bool cullBack) {
  Pst p{e0, e1};
  const float n = float(views);
  const float dL = p.width(0.0f), dR = p.width(n);
  auto add = [&](float top, float bottom, bool front) {
    if (bottom > top && (front || !cullBack)) p.pieces[p.pieceCount++] = {top, bottom, front};
  };
  if ((dL < 0 && dR > 0) || (dL > 0 && dR < 0)) {
    const float rStar = n * dL / (dL - dR);  // Halle 5.6.3: the edge-on view
    add(0.0f, rStar, dL > 0);
    add(rStar, n, dR > 0);
  } else if (dL != 0 || dR != 0) {
    add(0.0f, n, dL + dR > 0);
  }
  return p;
}

glm::vec3 pstColor(const Pst& pst, bool front, float u) {
  const glm::vec3 c0 = front ? pst.e0.frontOverW : pst.e0.backOverW;
  const glm::vec3 c1 = front ? pst.e1.frontOverW : pst.e1.backOverW;
  const float invW = pst.e0.invW + (pst.e1.invW - pst.e0.invW) * u;
  return (c0 + (c1 - c0) * u) / invW;
}

float pstDepth(const Pst& pst, float u) { return pst.e0.depth + (pst.e1.depth - pst.e0.depth) * u; }

}  // namespace mvr
