#include "mvr/backends/warp/warp_spans.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "epi/diffuse_spans.h"
#include "mvr/backends/warp/depth_warp.h"
#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/parallel.h"
#include "mvr/views/outline_triangles.h"

namespace mvr {

namespace {

constexpr float kPi = 3.14159265358979f;
using spans::F4;  // epi/diffuse_spans.h: four lanes, each IEEE single precision

inline F4 abs4(F4 v) { return v < 0.0f ? -v : v; }
inline F4 min4(F4 a, F4 b) { return a < b ? a : b; }
inline F4 max4(F4 a, F4 b) { return a < b ? b : a; }

// atan2(y, x) for y >= 0, within 1e-5 of it: the odd minimax polynomial
// of atan on [0, 1], folded by atan(r) = pi/2 - atan(1/r) and pi - ...
inline F4 atan2Upper(F4 y, F4 x) {
  const F4 ax = abs4(x), hi = max4(ax, y), lo = min4(ax, y);
  const F4 r = lo / max4(hi, F4{} + 1e-30f), r2 = r * r;
  F4 a = r * (0.99997726f +
              r2 * (-0.33262347f + r2 * (0.19354346f + r2 * (-0.11643287f + r2 * (0.05265332f + r2 * -0.01172120f)))));
  a = y > ax ? 0.5f * kPi - a : a;
  return x < 0.0f ? kPi - a : a;
}

// cos(pi s) for s in [0, 1], within 4e-6: -sin(pi (s - 1/2)) by its
// Taylor polynomial to the ninth power on [-pi/2, pi/2].
inline F4 cosPi(F4 s) {
  const F4 x = kPi * (s - 0.5f), x2 = x * x;
  return -x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
}

template <PixelType T>
inline void encodePixel(const Srgb8Encoder& srgb, const float* rgb, uint8_t* out) {
  if constexpr (T == PixelType::F32) {
    const float rgba[4] = {rgb[0], rgb[1], rgb[2], 1.0f};
    std::memcpy(out, rgba, sizeof rgba);
  } else {
    for (int c = 0; c < 3; ++c)
      out[c] = T == PixelType::Srgb8 ? srgb(rgb[c]) : uint8_t(std::lrint(std::clamp(rgb[c], 0.0f, 1.0f) * 255.0f));
    out[3] = 255;
  }
}

template <PixelType T>
using TypeTag = std::integral_constant<PixelType, T>;

}  // namespace

// One reference's scanline as points that move along it: its pixel
// centres with samples, and where the first or last pixel has one, the
// image's edge (the GL grid's border ring: x 0 and W, that pixel's values),
// and beside an empty pixel the silhouette inside it, where the source
// measured one on the pixel's surface (RgbdView::ends).
struct WarpSpans::Row {
  enum : uint8_t { kNone, kSurface, kSheet };
  std::vector<float> x0, slope, inv, rgb, occ;
  std::vector<uint8_t> next;   // the segment to the next point
  std::vector<uint8_t> splat;  // a silhouette pixel: also its own footprint
  std::vector<float> far;      // a sheet's farther end's camera z
  const float* depth = nullptr;  // the reference's camera z along the scanline
};

struct WarpSpans::Line {
  std::vector<float> inv, rgb;  // 1 / camera z (0: nothing drawn), colour
  std::vector<uint8_t> occ;
  int lo = 0, hi = 0;  // the pixels drawn lie in [lo, hi)
  explicit Line(int w) : inv(size_t(w)), rgb(3 * size_t(w)), occ(size_t(w)) {}
};

WarpSpans::WarpSpans(const ShearingCamera& cam, int row, PixelType type, float tau, float a)
    : cam_(cam), row_(row), type_(type), tau_(tau), a_(a) {
  perUnit_ = cam.width() / cam.planeWidth();
  focal_ = perUnit_ * cam.spec().distance;
}

int WarpSpans::add(std::shared_ptr<const RgbdView> view, double x) {
  if (view->color.type != PixelType::F32 || view->color.width != cam_.width() ||
      view->color.height != cam_.height() || view->depth.width != cam_.width() || view->depth.height != cam_.height())
    fail("warp", "a reference is not a float image of the camera's size");
  Reference r{std::move(view), x, {}, {}};
  std::vector<uint32_t> silhouettes;
  labelPixels(r.view->depth, tau_, r.labels, silhouettes);
  r.silhouette.assign(r.labels.size(), 0);
  for (const uint32_t p : silhouettes) r.silhouette[p] = 1;
  refs_.push_back(std::move(r));
  centres_.emplace_back(x, 0.0, 0.0);
  return int(refs_.size()) - 1;
}

std::pair<int, int> WarpSpans::pairOf(int view) const {
  // Centres along the track: distances and directions there are the 3D ones.
  return nearestPair(centres_, glm::dvec3(cam_.viewX(view), 0.0, 0.0));
}

WarpSpans::Row WarpSpans::rowOf(int ref, int j) const {
  const Reference& reference = refs_[size_t(ref)];
  const RgbdView& v = *reference.view;
  const int w = cam_.width();
  const size_t base = size_t(j) * w;
  const float* depth = v.depth.values.data() + base;
  const float* color = reinterpret_cast<const float*>(v.color.bytes.data()) + 4 * base;
  Row r;
  r.depth = depth;
  auto point = [&](float x, int i, bool splat, float z) {
    const float inv = 1.0f / z;
    r.x0.push_back(x);
    r.slope.push_back(float(perUnit_ - focal_ * double(inv)));
    r.inv.push_back(inv);
    r.rgb.insert(r.rgb.end(), color + 4 * i, color + 4 * i + 3);
    r.occ.push_back(reference.labels[base + size_t(i)]);
    r.splat.push_back(splat);
    r.next.push_back(Row::kNone);
    r.far.push_back(0.0f);
  };
  for (int i = 0; i < w; ++i) {
    if (!(depth[i] > 0.0f)) continue;
    if (i == 0) {
      point(0.0f, 0, false, depth[0]);
      r.next.back() = Row::kSurface;
    }
    // Beside an empty pixel the segment goes on to the silhouette measured
    // inside the pixel, where the source has one on the same surface.
    const PixelEnds e = v.ends.empty() ? PixelEnds{} : v.ends[base + size_t(i)];
    auto onSurface = [&](float z) { return z > 0.0f && oneSurface(z, depth[i], tau_); };
    const bool openL = outlineRead(depth, w, i, -1), openR = outlineRead(depth, w, i, +1);
    const bool endL = openL && e.right >= 0.0f && onSurface(e.leftZ);
    const bool endR = openR && e.right >= 0.0f && onSurface(e.rightZ);
    if (endL) {
      point(float(i) + e.left, i, false, e.leftZ);
      r.next.back() = Row::kSurface;
    }
    // A silhouette pixel with an open side it has no end on keeps its
    // footprint; so does one whose empty neighbours lie above or below.
    const bool silhouette = reference.silhouette[base + size_t(i)] != 0;
    point(float(i) + 0.5f, i, silhouette && ((openL && !endL) || (openR && !endR) || !(endL || endR)), depth[i]);
    if (endR) {
      r.next.back() = Row::kSurface;
      point(float(i) + e.right, i, false, e.rightZ);
    } else if (i + 1 < w && depth[i + 1] > 0.0f) {
      const bool sheet = !oneSurface(depth[i], depth[i + 1], tau_);  // GridTriangles' jump
      r.next.back() = sheet ? Row::kSheet : Row::kSurface;
      r.far.back() = std::max(depth[i], depth[i + 1]);
    } else if (i + 1 == w) {
      r.next.back() = Row::kSurface;
      point(float(w), i, false, depth[i]);
    }
  }
  return r;
}

// One reference's scanline (at camera x refX) in the view at camera x
// eyeX: its segments and footprints filled with a depth test, its sheets'
// fragments dropped where the other reference (at camera x otherX) sees
// through them (kWarpFragment's SHEET test, along the one row it takes
// place on here).
void WarpSpans::warp(const Row& r, double refX, const Row* other, double otherX, double eyeX, Line& out) const {
  const int w = cam_.width();
  if (out.hi > out.lo) std::fill(out.inv.begin() + out.lo, out.inv.begin() + out.hi, 0.0f);
  out.lo = w, out.hi = 0;
  const size_t n = r.x0.size();
  if (!n) return;
  // Each point's place in the view, and the first pixel whose centre lies
  // at or right of it: a segment covers the pixels from its left end's to
  // its right end's, [lo, hi) in centres.
  const float t = float(eyeX - refX);
  thread_local std::vector<float> x;
  thread_local std::vector<int> first;
  x.resize(n), first.resize(n);
  for (size_t k = 0; k < n; ++k) {
    x[k] = r.x0[k] + t * r.slope[k];
    first[k] = std::clamp(spans::ceilToInt(x[k] - 0.5f), 0, w);
  }
  float* const zbuffer = out.inv.data();
  float* const color = out.rgb.data();
  uint8_t* const label = out.occ.data();
  const float* const inv = r.inv.data();
  const float* const rgb = r.rgb.data();
  const float* const occ = r.occ.data();
  const float toOther = float(otherX - eyeX);
  for (size_t k = 0; k + 1 < n; ++k) {
    if (r.next[k] == Row::kNone) continue;
    const int p0 = std::min(first[k], first[k + 1]), p1 = std::max(first[k], first[k + 1]);
    if (p0 >= p1) continue;
    out.lo = std::min(out.lo, p0), out.hi = std::max(out.hi, p1);
    const float xa = x[k], perPixel = 1.0f / (x[k + 1] - xa);
    const float invA = inv[k], invStep = inv[k + 1] - inv[k];
    const float* ca = rgb + 3 * k;
    const float dc[3] = {ca[3] - ca[0], ca[4] - ca[1], ca[5] - ca[2]};
    const bool sheet = r.next[k] == Row::kSheet && other;
    const bool oneLabel = occ[k] == occ[k + 1];
    for (int p = p0; p < p1; ++p) {
      const float s = (float(p) + 0.5f - xa) * perPixel;
      const float z = invA + s * invStep;
      if (!(z > zbuffer[p])) continue;
      if (sheet && seenThrough(*other, float(p) + 0.5f, z, 1.0f / r.far[k], toOther)) continue;
      // Colour is linear in the window position (both views divide by the
      // same camera z); the label perspective-correct, as GL interpolates it.
      zbuffer[p] = z;
      float* c = color + 3 * size_t(p);
      c[0] = ca[0] + s * dc[0], c[1] = ca[1] + s * dc[1], c[2] = ca[2] + s * dc[2];
      const float lambda = s * inv[k + 1] / z;
      label[p] = oneLabel ? occ[k] > 0.5f : occ[k] + lambda * (occ[k + 1] - occ[k]) > 0.5f;
    }
  }
  for (size_t k = 0; k < n; ++k) {
    if (!r.splat[k]) continue;
    // The pixels whose centres lie in [x - 1/2, x + 1/2).
    const int p0 = std::max(0, spans::ceilToInt(x[k] - 1.0f)), p1 = std::min(w, spans::ceilToInt(x[k]));
    for (int p = p0; p < p1; ++p) {
      if (!(inv[k] > zbuffer[p])) continue;
      zbuffer[p] = inv[k];
      std::copy_n(rgb + 3 * k, 3, color + 3 * size_t(p));
      label[p] = occ[k] > 0.5f;
      out.lo = std::min(out.lo, p), out.hi = std::max(out.hi, p + 1);
    }
  }
}

// A sheet's fragment at pixel centre x and 1/z inv stands for a surface on
// the view's ray between it and 1/z invFar. The other reference, toOther
// from the eye along the track, sees that stretch along its own scanline:
// it is empty where at every pixel it crosses that reference sees nothing
// or a surface beyond the ray's point.
bool WarpSpans::seenThrough(const Row& other, float x, float inv, float invFar, float toOther) const {
  if (toOther == 0.0f) return false;
  invFar = std::min(invFar, inv);
  const int w = cam_.width();
  const float unit = float(perUnit_), focal = float(focal_);
  auto at = [&](float i) { return x + toOther * (unit - focal * i); };  // the point of 1/z i, in the other reference
  const float from = at(inv), to = at(invFar);
  const int steps = int(std::min(std::ceil(std::abs(to - from)), float(w + cam_.height())));
  for (int k = 0; k <= steps; ++k) {
    const float u = steps > 0 ? from + (to - from) * (float(k) / float(steps)) : from;
    const float i = std::clamp((unit - (u - x) / toOther) / focal, invFar, inv);
    const float px = std::floor(at(i));
    if (px < 0.0f || px >= float(w)) return false;
    const float seen = other.depth[int(px)];
    if (seen > 0.0f && seen < (1.0f + tau_) / i) return false;
  }
  return true;
}

// View `view`'s scanline from the two lines (l1 null: l0 alone), encoded.
void WarpSpans::composite(const Line& l0, const Line* l1, int j, int view, int a, int b, uint8_t* out) const {
  const int w = cam_.width();
  const size_t bytes = 4 * Image::channelBytes(type_);
  std::memset(out, 0, size_t(w) * bytes);
  const glm::dmat3 K = cam_.intrinsics(view, row_);
  const float fx = float(K[0][0]), cx = float(K[2][0]), fy = float(K[1][1]), cy = float(K[2][1]);
  const float yRatio = (float(j) + 0.5f - cy) / fy;  // camera y / z along the scanline
  const double eye = cam_.viewX(view);
  const float baseA = float(refs_[size_t(a)].x - eye), baseB = b < 0 ? 0.0f : float(refs_[size_t(b)].x - eye);
  const int lo = l1 ? std::min(l0.lo, l1->lo) : l0.lo, hi = l1 ? std::max(l0.hi, l1->hi) : l0.hi;
  // Per pixel the angle ratio s = theta0 / (theta0 + theta1) at the
  // nearer surface point and cos(pi s), four at a time: the surface point
  // in the plane of the track and the point, h its distance from the
  // track, u its foot's offset from the eye; the angle at it between the
  // eye and a reference `base` along the track.
  // and from those the weight of eq. 5-3 (compositeWeight), used where both
  // lines have the pixel.
  thread_local std::vector<float> weight;
  weight.resize(size_t(w) + 4);
  if (l1) {
    const float hPerZ = std::sqrt(1.0f + yRatio * yRatio);
    for (int p = lo & ~3; p < hi; p += 4) {
      F4 inv, x, inv0, inv1, occ0, occ1;
      for (int k = 0; k < 4; ++k) {
        const size_t q = size_t(std::min(p + k, w - 1));
        inv0[k] = l0.inv[q], inv1[k] = l1->inv[q];
        occ0[k] = float(l0.occ[q]), occ1[k] = float(l1->occ[q]);
        inv[k] = std::max({inv0[k], inv1[k], 1e-30f});
        x[k] = float(p + k) + 0.5f;
      }
      const F4 z = 1.0f / inv, h = z * hPerZ, u = (x - cx) * z / fx;
      auto angle = [&](float base) { return atan2Upper(std::abs(base) * h, h * h + (base - u) * -u); };
      const F4 t0 = angle(baseA), t1 = angle(baseB), sum = t0 + t1;
      const F4 s = sum > 0.0f ? t0 / max4(sum, F4{} + 1e-30f) : F4{} + 0.5f;
      // Lanes one line lacks get a weight that is not used.
      const F4 tiny = F4{} + 1e-30f;
      const F4 wgt = compositeWeightOf(s, cosPi(s), 1.0f / max4(inv0, tiny), 1.0f / max4(inv1, tiny), occ0, occ1, tau_, a_);
      std::memcpy(&weight[size_t(p)], &wgt, sizeof wgt);
    }
  }
  const Srgb8Encoder srgb;
  auto run = [&](auto type) {
    constexpr PixelType T = decltype(type)::value;
    for (int p = lo; p < hi; ++p) {
      const bool seen0 = l0.inv[size_t(p)] > 0.0f, seen1 = l1 && l1->inv[size_t(p)] > 0.0f;
      if (!seen0 && !seen1) continue;
      if (!seen1 || !seen0) {
        encodePixel<T>(srgb, seen0 ? &l0.rgb[3 * size_t(p)] : &l1->rgb[3 * size_t(p)], out + size_t(p) * bytes);
        continue;
      }
      const float wgt = weight[size_t(p)];
      const float* c0 = &l0.rgb[3 * size_t(p)];
      const float* c1 = &l1->rgb[3 * size_t(p)];
      const float rgb[3] = {c1[0] + wgt * (c0[0] - c1[0]), c1[1] + wgt * (c0[1] - c1[1]),
                            c1[2] + wgt * (c0[2] - c1[2])};
      encodePixel<T>(srgb, rgb, out + size_t(p) * bytes);
    }
  };
  switch (type_) {
    case PixelType::U8: return run(TypeTag<PixelType::U8>{});
    case PixelType::Srgb8: return run(TypeTag<PixelType::Srgb8>{});
    case PixelType::F32: return run(TypeTag<PixelType::F32>{});
  }
}

void WarpSpans::fillEpi(int j, const PixelRows& epi) const {
  if (epi.width != cam_.width() || epi.height != cam_.views() || epi.type != type_)
    fail("warp", "EPI memory of the wrong shape");
  if (refs_.empty()) fail("warp", "no references");
  std::vector<Row> rows;
  for (int k = 0; k < int(refs_.size()); ++k) rows.push_back(rowOf(k, j));
  Line l0(cam_.width()), l1(cam_.width());
  for (int view = 0; view < cam_.views(); ++view) {
    const auto [a, b] = pairOf(view);
    const double eye = cam_.viewX(view);
    const double xa = refs_[size_t(a)].x, xb = b < 0 ? xa : refs_[size_t(b)].x;
    warp(rows[size_t(a)], xa, b < 0 ? nullptr : &rows[size_t(b)], xb, eye, l0);
    if (b >= 0) warp(rows[size_t(b)], xb, &rows[size_t(a)], xa, eye, l1);
    composite(l0, b < 0 ? nullptr : &l1, j, view, a, b, epi.row(view));
  }
}

long WarpSpans::holes(int a, int b, int view) const {
  const int h = cam_.height();
  const double eye = cam_.viewX(view);
  std::atomic<long> count{0};
  constexpr int kBand = 16;
  parallelFor(0, (h + kBand - 1) / kBand, [&](int band) {
    Line l0(cam_.width()), l1(cam_.width());
    long local = 0;
    for (int j = band * kBand; j < std::min(h, (band + 1) * kBand); ++j) {
      // As DepthWarp::holes: each reference warped alone, sheets untested.
      warp(rowOf(a, j), refs_[size_t(a)].x, nullptr, 0.0, eye, l0);
      warp(rowOf(b, j), refs_[size_t(b)].x, nullptr, 0.0, eye, l1);
      for (size_t p = 0; p < l0.inv.size(); ++p) {
        const bool seen0 = l0.inv[p] > 0.0f, seen1 = l1.inv[p] > 0.0f;
        local += (seen0 || seen1) && (!seen0 || l0.occ[p]) && (!seen1 || l1.occ[p]);
      }
    }
    count += local;
  });
  return count;
}

}  // namespace mvr
