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

}  // namespace mvr
