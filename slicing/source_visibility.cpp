#include "slicing/source_visibility.h"

#include <algorithm>
#include <cmath>

namespace mvr {

TrackParallax::TrackParallax(const ShearingCamera& cam) : cam_(cam) {
  const CameraSpec& s = cam.spec();
  const double n = s.nearDistance, f = s.farDistance;
  pixelsPerDepth_ = s.distance * (cam.width() / cam.planeWidth()) * (f - n) / (n * f);
}

double TrackParallax::shift(float depth, double from, double to) const {
  const CameraSpec& s = cam_.spec();
  const double n = s.nearDistance, f = s.farDistance;
  const double w = n * f / (double(depth) * (f - n) + n);  // distance from the camera plane
  return (to - from) * cam_.disparityPerUnitTrack(s.distance - w);
}

double TrackParallax::reach(double x) const {
  return std::max(std::abs(x - cam_.viewX(0)), std::abs(x - cam_.viewX(cam_.views() - 1)));
}

namespace {

// Running counts of flagged entries: the flags in [a, b] are
// at(b + 1) - at(a).
class PrefixCount {
 public:
  void reset(size_t n) { sum_.assign(n + 1, 0); }
  void set(size_t i, bool flag) { sum_[i + 1] = sum_[i] + (flag ? 1 : 0); }
  int in(int a, int b) const { return b < a ? 0 : sum_[size_t(b) + 1] - sum_[size_t(a)]; }

 private:
  std::vector<int> sum_;
};

// Whether pixel x of an empty gap in the view at eyeX is a disocclusion
// hole rather than background: whatever fills it lies at about the depth
// of one of the gap's two sides, and there every source's nearest layer
// must cover it (were it background, some source would see background).
bool isHole(const std::vector<const SourceLayer*>& layers, const TrackParallax& parallax, int j,
            int x, double eyeX, const float sides[2]) {
  for (const SourceLayer* l : layers) {
    if (l->layer != 0) continue;
    const int w = l->color.width;
    for (int k = 0; k < 2; ++k) {
      const double at = x + 0.5 + parallax.shift(sides[k], eyeX, l->eye.x);
      if (at < 0.0 || at >= w || l->depth[size_t(j) * w + size_t(at)] == 0.0f) return false;
    }
  }
  return true;
}

}  // namespace

long hideInvisible(const SourceLayer& front, SourceLayer& back, const ShearingCamera& cam,
                   float overlap) {
  const int w = cam.width(), h = cam.height();
  const TrackParallax parallax(cam);
  // Pixels of relative motion per unit of depth difference, at the
  // farthest view from the source.
  const double k = parallax.reach(front.eye.x) * parallax.pixelsPerDepth();
  PrefixCount empty, cracks;
  long kept = 0;
  for (int j = 0; j < h; ++j) {
    const float* fd = front.depth.data() + size_t(j) * w;
    float* bd = back.depth.data() + size_t(j) * w;
    empty.reset(w);
    cracks.reset(w);
    float lo = 1.0f, hi = 0.0f;
    for (int x = 0; x < w; ++x) {
      empty.set(x, fd[x] == 0.0f);
      cracks.set(x, x + 1 < w && std::abs(fd[x + 1] - fd[x]) * k > 2.0 * overlap);
      if (fd[x] > 0.0f) lo = std::min(lo, fd[x]), hi = std::max(hi, fd[x]);
    }
    for (int x = 0; x < w; ++x) {
      if (bd[x] == 0.0f) continue;
      const int r = int(std::ceil(k * std::max(hi - bd[x], bd[x] - lo))) + 1;
      const bool covered = x - r >= 0 && x + r < w && empty.in(x - r, x + r) == 0 &&
                           cracks.in(x - r, x + r - 1) == 0;
      if (covered)
        bd[x] = 0.0f;
      else
        ++kept;
    }
  }
  return kept;
}

long countHoles(const std::vector<const SourceLayer*>& layers, const ShearingCamera& cam,
                double eyeX, float overlap) {
  const int w = cam.width(), h = cam.height();
  const TrackParallax parallax(cam);
  float lo = 1.0f, hi = 0.0f;
  double farthest = 0.0;
  for (const SourceLayer* layer : layers) {
    farthest = std::max(farthest, std::abs(eyeX - layer->eye.x));
    for (float d : layer->depth)
      if (d > 0.0f) lo = std::min(lo, d), hi = std::max(hi, d);
  }
  // The widest gap the depth range can open between a source and eyeX.
  const int widest = int(std::ceil(farthest * parallax.pixelsPerDepth() * std::max(0.0f, hi - lo))) + 1;
  long holes = 0;
  std::vector<float> covered(w);  // nearest splatted depth, 0 where empty
  for (int j = 0; j < h; ++j) {
    std::fill(covered.begin(), covered.end(), 0.0f);
    for (const SourceLayer* layer : layers) {
      const float* depth = layer->depth.data() + size_t(j) * w;
      for (int x = 0; x < w; ++x) {
        if (depth[x] == 0.0f) continue;
        const double at = x + parallax.shift(depth[x], layer->eye.x, eyeX);
        // Pixel centres c + 0.5 in [at - overlap, at + 1 + overlap).
        const int first = std::max(0, int(std::ceil(at - overlap - 0.5)));
        const int last = std::min(w, int(std::ceil(at + 1.0 + overlap - 0.5)));
        for (int c = first; c < last; ++c) covered[c] = std::max(covered[c], depth[x]);
      }
    }
    for (int x = 0, lastCovered = -1; x < w; ++x) {
      if (covered[x] == 0.0f) continue;
      const int gap = x - lastCovered - 1;
      if (lastCovered >= 0 && gap > 0 && gap <= widest) {
        const float sides[2] = {covered[lastCovered], covered[x]};
        for (int c = lastCovered + 1; c < x; ++c) holes += isHole(layers, parallax, j, c, eyeX, sides);
      }
      lastCovered = x;
    }
  }
  return holes;
}

}  // namespace mvr
