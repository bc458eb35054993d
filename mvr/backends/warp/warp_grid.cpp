#include "mvr/backends/warp/warp_grid.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

namespace mvr {

int gridPixel(int k, int n) { return std::clamp(int(std::floor(std::clamp(float(k) - 0.5f, 0.0f, float(n)))), 0, n - 1); }

namespace {

class GridTriangles {
 public:
  GridTriangles(const DepthImage& d, const std::vector<float>& labels, float tau, float deviation)
      : tau_(tau), deviation_(deviation), gw_(d.width + 2), gh_(d.height + 2), valid_(size_t(gw_) * gh_),
        flat_(size_t(gw_) * gh_), inverse_(size_t(gw_) * gh_), merged_(size_t(gw_) * gh_) {
    for (int j = 0; j < gh_; ++j)
      for (int i = 0; i < gw_; ++i) {
        const int x = gridPixel(i, d.width), y = gridPixel(j, d.height);
        const size_t k = at(i, j);
        valid_[k] = d.at(x, y) > 0.0f;
        inverse_[k] = valid_[k] ? 1.0f / d.at(x, y) : 0.0f;
        // The border ring's vertices sit at the image's edge, off the
        // pixel-centre spacing: never inside a merged rectangle.
        flat_[k] = valid_[k] && labels[size_t(y) * d.width + x] == 0.0f && i > 0 && i + 1 < gw_ && j > 0 &&
                   j + 1 < gh_;
      }
  }

  GridLists lists() {
    std::vector<uint32_t> out, sheets;
    auto cell = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (!valid_[a] || !valid_[b] || !valid_[c]) return;
      if (!jump(a, b, c)) {
        out.insert(out.end(), {a, b, c});
        return;
      }
      while (inverse_[c] > std::min(inverse_[a], inverse_[b])) std::tie(a, b, c) = std::tuple(b, c, a);
      sheets.insert(sheets.end(), {a, b, c});
    };
    for (int j = 0; j + 1 < gh_; ++j)
      for (int i = 0; i + 1 < gw_; ++i) {
        if (merged_[at(i, j)]) continue;
        const auto [i1, j1] = rectangle(i, j);
        const uint32_t a = uint32_t(at(i, j));
        if (i1 > i) {
          const uint32_t b = uint32_t(at(i1, j)), c = uint32_t(at(i, j1)), e = uint32_t(at(i1, j1));
          out.insert(out.end(), {a, b, c, b, e, c});
          for (int y = j; y < j1; ++y) std::fill_n(merged_.begin() + ptrdiff_t(at(i, y)), i1 - i, uint8_t(1));
          continue;
        }
        const uint32_t b = a + 1, c = a + uint32_t(gw_), e = c + 1;
        cell(a, b, c);
        cell(b, e, c);
      }
    const size_t start = out.size();
    out.insert(out.end(), sheets.begin(), sheets.end());
    return {std::move(out), start};
  }

 private:
  static constexpr int kLongest = 32;  // cells along a side of a rectangle
  // Beside the allowed deviation, float rounding of 1/z and of the fit.
  static constexpr float kRounding = 1e-6f;

  size_t at(int i, int j) const { return size_t(j) * gw_ + i; }

  // Vertices whose depths differ by more than tau of the nearer.
  bool jump(uint32_t a, uint32_t b, uint32_t c) const {
    const float near = std::max({inverse_[a], inverse_[b], inverse_[c]});
    const float far = std::min({inverse_[a], inverse_[b], inverse_[c]});
    return 1.0f / far - 1.0f / near > tau_ / near;
  }

  // 1/z = p0 + si (i - i0) + sj (j - j0): the plane of a rectangle whose
  // top left vertex is (i0, j0).
  struct Plane {
    float p0, si, sj;
    int i0, j0;
    float operator()(int i, int j) const { return p0 + si * float(i - i0) + sj * float(j - j0); }
  };

  // The plane through vertex (i0, j0), (i1, j0) and (i0, j1) (chords,
  // not the next vertices' slopes: on a curved surface a chord strays a
  // quarter as far over the same length), if every vertex of the
  // rectangle lies on it.
  std::optional<Plane> fit(int i0, int j0, int i1, int j1) const {
    const float p0 = inverse_[at(i0, j0)];
    const Plane p{p0, (inverse_[at(i1, j0)] - p0) / float(i1 - i0), (inverse_[at(i0, j1)] - p0) / float(j1 - j0),
                  i0, j0};
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t k = at(i, j);
        if (!flat_[k] || std::abs(p(i, j) - inverse_[k]) > deviation_ + kRounding * inverse_[k])
          return std::nullopt;
      }
    return p;
  }

  // The rectangle of free cells on one plane from cell (i, j), widest
  // first; returns its far vertex (i1, j1), i1 == i when there is none.
  std::pair<int, int> rectangle(int i, int j) const {
    if (!fit(i, j, i + 1, j + 1)) return {i, j};
    int i1 = i + 1;
    while (i1 + 1 < gw_ && i1 + 1 - i <= kLongest && !merged_[at(i1, j)] && fit(i, j, i1 + 1, j + 1)) ++i1;
    int j1 = j + 1;
    while (j1 + 1 < gh_ && j1 + 1 - j <= kLongest && fit(i, j, i1, j1 + 1)) ++j1;
    return {i1, j1};
  }

  float tau_, deviation_;  // deviation: of 1/z from a merged rectangle's plane, at most
  int gw_, gh_;
  std::vector<uint8_t> valid_, flat_;
  std::vector<float> inverse_;
  std::vector<uint8_t> merged_;  // cells already inside a rectangle
};

}  // namespace

GridLists gridTriangles(const DepthImage& depth, const std::vector<float>& labels, float tau, float deviation) {
  return GridTriangles(depth, labels, tau, deviation).lists();
}

Splats makeSplats(const std::vector<uint32_t>& pixels, int width) {
  Splats s;
  for (const uint32_t pixel : pixels) {
    const glm::vec2 centre(float(pixel % uint32_t(width)) + 0.5f, float(pixel / uint32_t(width)) + 0.5f);
    const uint32_t k = uint32_t(s.vertices.size());
    for (const glm::vec2 corner : {glm::vec2(-0.5f, -0.5f), glm::vec2(0.5f, -0.5f), glm::vec2(-0.5f, 0.5f),
                                   glm::vec2(0.5f, 0.5f)})
      s.vertices.emplace_back(centre + corner, centre);
    s.indices.insert(s.indices.end(), {k, k + 1, k + 2, k + 1, k + 3, k + 2});
  }
  return s;
}

}  // namespace mvr
