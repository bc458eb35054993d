#include "mvr/backends/interp/source_blend.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace mvr {

namespace {

// Colours (linear, per channel) closer than this are one surface seen from
// both sources; farther apart, the two sources see different surfaces
// there (an occlusion one of them resolves wrongly) and the joint pixel,
// depth-tested, stands.
constexpr float kSameSurface = 0.1f;

// Per pixel of one EPI row: whether the source sees background there. A
// run of pixels the source leaves empty is background where it reaches the
// row's end or a pixel the joint EPI leaves empty too: beyond the other
// source's outline lies what both see as empty. A run the joint covers
// from end to end is a crack between the source's slices or a hole it
// could not see into (the other source fills it), not background.
void markBackground(const Image& epi, const Image& joint, int view, std::vector<uint8_t>& background) {
  const int w = epi.width;
  background.assign(size_t(w), 0);
  for (int x = 0; x < w;) {
    if (epi.pixel(x, view).a > 0.0f) {
      ++x;
      continue;
    }
    int end = x;
    bool open = x == 0;
    for (; end < w && epi.pixel(end, view).a == 0.0f; ++end) open = open || joint.pixel(end, view).a == 0.0f;
    if (open || end == w) std::fill(background.begin() + x, background.begin() + end, 1);
    x = end;
  }
}

double angleAt(const glm::dvec3& p, const glm::dvec3& e0, const glm::dvec3& e1) {
  const glm::dvec3 u = e0 - p, v = e1 - p;
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

}  // namespace

double sourceWeight(Blend mode, const ShearingCamera& interval, int row, int scanline, int view, int x) {
  const int last = interval.views() - 1;
  if (last <= 0 || mode == Blend::None) return 1.0;
  if (mode == Blend::Track) return 1.0 - double(view) / last;
  // The pixel's point on the image plane (z = 0), and the angles there
  // between the rays to this view's eye and to each source's.
  const glm::dvec3 p((double(x) + 0.5) / interval.width() * interval.planeWidth() - 0.5 * interval.planeWidth(),
                     0.5 * interval.planeHeight() - (double(scanline) + 0.5) / interval.height() * interval.planeHeight(),
                     0.0);
  const glm::dvec3 eye = interval.eye(view, row);
  const double ta = angleAt(p, eye, interval.eye(0, row)), tb = angleAt(p, eye, interval.eye(last, row));
  const double s = ta + tb > 0.0 ? ta / (ta + tb) : double(view) / last;
  return 0.5 * (1.0 + std::cos(std::numbers::pi * s));
}

void blendEpi(Blend mode, const ShearingCamera& interval, int row, int scanline, const Image& a, const Image& b,
              Image& joint, int firstView) {
  std::vector<uint8_t> aBackground, bBackground;
  for (int v = 0; v < joint.height; ++v) {
    markBackground(a, joint, v, aBackground);
    markBackground(b, joint, v, bBackground);
    for (int x = 0; x < joint.width; ++x) {
      const glm::vec4 j = joint.linear(x, v);
      if (j.a == 0.0f) continue;
      const glm::vec4 pa = a.linear(x, v), pb = b.linear(x, v);
      const auto w = float(sourceWeight(mode, interval, row, scanline, firstView + v, x));
      if (pa.a > 0.0f && pb.a > 0.0f) {
        const glm::vec3 d = glm::abs(glm::vec3(pa) - glm::vec3(pb));
        if (std::max({d.r, d.g, d.b}) <= kSameSurface) joint.setLinear(x, v, w * pa + (1.0f - w) * pb);
      } else if (pa.a > 0.0f && bBackground[size_t(x)]) {
        joint.setLinear(x, v, glm::vec4(glm::vec3(j), w));
      } else if (pb.a > 0.0f && aBackground[size_t(x)]) {
        joint.setLinear(x, v, glm::vec4(glm::vec3(j), 1.0f - w));
      }
    }
  }
}

}  // namespace mvr
