#include "slicing/image_slices.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

#include "mvr/error.h"
#include "mvr/parallel.h"
#include "slicing/highlight_splits.h"
#include "slicing/source_visibility.h"

namespace mvr {
namespace {

constexpr int kMaxLevel = std::countr_zero(unsigned(shading::TextureVectors::kMaxLength));

// Min and max window depth of every aligned block of 2^l pixels of one
// scanline. An empty pixel (or one kept alone) spans everything, so no
// block holding it is ever close enough to coalesce.
class DepthMip {
 public:
  // alone (may be null): pixels that must stay slices of their own.
  DepthMip(const float* depth, const uint8_t* alone, int width) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    lo_.emplace_back(width), hi_.emplace_back(width);
    for (int x = 0; x < width; ++x) {
      const bool empty = depth[x] == 0.0f || (alone && alone[x]);
      lo_[0][x] = empty ? -inf : depth[x];
      hi_[0][x] = empty ? inf : depth[x];
    }
    for (int l = 1; l <= kMaxLevel && (width >> l) > 0; ++l) {
      const int n = width >> l;
      lo_.emplace_back(n), hi_.emplace_back(n);
      for (int i = 0; i < n; ++i) {
        lo_[l][i] = std::min(lo_[l - 1][2 * i], lo_[l - 1][2 * i + 1]);
        hi_[l][i] = std::max(hi_[l - 1][2 * i], hi_[l - 1][2 * i + 1]);
      }
    }
  }
  int levels() const { return int(lo_.size()); }
  // Depth range of block i of level l.
  float range(int l, int i) const { return hi_[l][i] - lo_[l][i]; }

 private:
  std::vector<std::vector<float>> lo_, hi_;
};

class LayerSlicer {
 public:
  LayerSlicer(const ShearingCamera& cam, int row, const ImageSliceOptions& options, ImageSlices& out)
      : cam_(cam), options_(options), out_(out), transform_(cam, row, out.vertices) {
    if (options.scene && options.splits > 0) highlights_.emplace(*options.scene, cam, row, options.splits);
  }

  // Scanlines [first, last) of the layer; other: the front layer of the
  // nearest other source, whose outline the slices meet in its view
  // (null: none).
  // front: the nearest layer of the layer's source.
  void slice(const SourceLayer& layer, int first, int last, const SourceLayer* other = nullptr,
             const SourceLayer* front = nullptr) {
    other_ = other;
    outlined_ = front && !front->outline.empty() ? front : nullptr;
    const int w = cam_.width();
    // Off: even equal depths stay apart. Never infinite (a track with no
    // width): a block holding an empty pixel spans an infinite range.
    const float tolerance =
        options_.coalesce > 0.0f
            ? std::min(coalesceDepthRange(cam_, layer.eye.x, options_.coalesce), std::numeric_limits<float>::max())
            : -1.0f;
    join_ = std::min(coalesceDepthRange(cam_, layer.eye.x, 2.0f * options_.overlap), std::numeric_limits<float>::max());
    const bool split = highlights_ && layer.normals.size() == layer.depth.size();
    std::vector<uint8_t> alone(split ? w : 0);
    for (int j = first; j < last; ++j) {
      const float* depth = layer.depth.data() + size_t(j) * w;
      for (int x = 0; split && x < w; ++x)
        alone[x] = highlights_->specular(materialOf(layer.normals[size_t(j) * w + x]));
      const DepthMip mip(depth, split ? alone.data() : nullptr, w);
      for (int x = 0; x < w;) {
        if (depth[x] == 0.0f) {
          ++x;
          continue;
        }
        // The largest aligned block from x whose depths agree.
        int l = 0;
        while (l + 1 < mip.levels() && x % (2 << l) == 0 && x + (2 << l) <= w &&
               mip.range(l + 1, x >> (l + 1)) <= tolerance)
          ++l;
        addRun(layer, j, x, 1 << l);
        x += 1 << l;
      }
    }
  }

  std::vector<uint32_t> scanlineOf;

 private:
  // Pixels [x, x + n) of scanline j as one slice: the ends on the line
  // through the first and last pixel centres (exact for a plane).
  void addRun(const SourceLayer& layer, int j, int x, int n) {
    const float* depth = layer.depth.data() + size_t(j) * cam_.width();
    const float d0 = depth[x], slope = n > 1 ? (depth[x + n - 1] - d0) / float(n - 1) : surfaceSlope(depth, x);
    const float oL = widening(x - 1), oR = widening(x + n);
    texels_.clear();
    for (int k = 0; k < n; ++k) texels_.push_back(glm::vec4(glm::vec3(layer.color.pixel(x + k, j)), 1.0f));
    const auto base = uint32_t(out_.vertices.vertexCount());
    const glm::vec3 c(texels_[0]);
    double ends[2] = {x - oL, x + n + oR};  // the ends' pixel x
    float d[2] = {d0 + (-oL - 0.5f) * slope, d0 + (float(n) + oR - 0.5f) * slope};
    bool onOutline[2] = {false, false};
    bool moved[2] = {false, false};  // ends inside the run's pixels, or beyond by the outline
    // A side that continues its neighbour's surface ends on their shared
    // boundary at the mean of the two centres' depths, as the neighbour's
    // slice does: the two meet in every view, so no crack opens between
    // them and neither stands over the other's pixel (widened by the
    // overlap instead, the nearer of the two took a quarter pixel of the
    // other's colour: bunny 160x120, 30.4 -> 30.7 dB with this alone).
    if (joined(depth, x, x - 1)) d[0] = 0.5f * (depth[x - 1] + depth[x]);
    if (joined(depth, x + n - 1, x + n)) d[1] = 0.5f * (depth[x + n - 1] + depth[x + n]);
    if (outlined_) {
      const size_t row = size_t(j) * cam_.width();
      const PixelOutline* outline = outlined_->outline.data() + row;
      const float* at = outlined_->depth.data() + row;
      const bool behind = outlined_ != &layer;
      onOutline[0] = outlineEnd(outline[x], at, x, -1, behind, ends[0], d[0]);
      onOutline[1] = outlineEnd(outline[x + n - 1], at, x + n - 1, +1, behind, ends[1], d[1]);
      moved[0] = onOutline[0], moved[1] = onOutline[1];
      if (behind) insetBehind(depth, x, n, slope, onOutline, ends, d, moved);
    }
    if (options_.fitRims && n == 1) {
      double e;
      float zt;
      if (!onOutline[0] && rimFit(depth, x, -1, e, zt)) ends[0] = e, d[0] = zt;
      if (!onOutline[1] && rimFit(depth, x, +1, e, zt)) ends[1] = e, d[1] = zt;
    }
    if (other_ && !outlined_) meetOtherOutline(layer, j, ends, d);
    for (int e = 0; e < 2; ++e)
      transform_.add(cam_.unprojectAt(layer.eye.x, layer.eye.y, {ends[e], j + 0.5, d[e]}), c, c, nullptr);
    out_.vertices.triangles.push_back({base, base + 1, base + 1});
    // The vector's texels span the run's pixels; an end on the outline or
    // inset lies elsewhere.
    SliceVector vector{out_.vertices.vectorTexels.addTexels(texels_), n,
                       moved[0] ? float(ends[0] - x) / float(n) : -oL / float(n),
                       moved[1] ? float(ends[1] - x) / float(n) : 1.0f + oR / float(n)};
    if (n == 1 && highlights_ && !layer.normals.empty()) {
      const glm::vec4 normal = layer.normals[size_t(j) * cam_.width() + x];
      const glm::vec3 p(cam_.unprojectAt(layer.eye.x, layer.eye.y, {x + 0.5, j + 0.5, d0}));
      vector.firstKnot = int(out_.vertices.knots.size());
      if (glm::length(glm::vec3(normal)) > 0.0f)
        vector.knotCount = highlights_->add(p, glm::normalize(glm::vec3(normal)), materialOf(normal),
                                            out_.vertices.knots);
    }
    out_.vertices.vectors.push_back(vector);
    scanlineOf.push_back(uint32_t(j));
    out_.pixels += size_t(n);
  }

  // A rim pixel's outline from the curvature of its surface: pixel i, its
  // neighbour at i + dir empty, the two inward of it covered and receding
  // toward it (reversed Z: depth falls toward the rim). Near a smooth
  // silhouette the surface's profile along the scanline is a parabola
  // u = ue - a (z - zt)^2, u the pixel offset along dir from i's centre,
  // with its vertex at the silhouette (offset ue, tangent depth zt).
  // Through the three centres (u = 0, -1, -2) the equal steps give
  // (z0 - z1)(z0 + z1 - 2 zt) = (z1 - z2)(z1 + z2 - 2 zt), so
  //   zt = (z0^2 + z2^2 - 2 z1^2) / (2 (z0 - 2 z1 + z2)),
  //   a  = -1 / ((z0 - z1)(z0 + z1 - 2 zt)),  ue = a (z0 - zt)^2.
  // A rim (a > 0) whose edge lies within the pixel (ue <= 0.5: the next
  // centre is empty) gets its outer end there at the tangent depth: the
  // end is then the silhouette point itself, which every other view sees
  // inside its outline, rather than a point of the pixel's flat footprint
  // whose track leaves the surface. Else the end stays on the boundary.
  bool rimFit(const float* depth, int i, int dir, double& edge, float& tangentDepth) const {
    const int w = cam_.width(), i1 = i - dir, i2 = i - 2 * dir;
    if ((i + dir >= 0 && i + dir < w && depth[i + dir] != 0.0f) || i2 < 0 || i2 >= w) return false;
    const double z0 = depth[i], z1 = depth[i1], z2 = depth[i2];
    if (z1 == 0.0 || z2 == 0.0 || !(z0 < z1 && z1 < z2)) return false;
    const double curvature = z0 - 2.0 * z1 + z2;
    if (std::abs(curvature) < 1e-9) return false;  // a plane ends at a crease, not a rim
    const double zt = (z0 * z0 + z2 * z2 - 2.0 * z1 * z1) / (2.0 * curvature);
    const double a = -1.0 / ((z0 - z1) * (z0 + z1 - 2.0 * zt));
    const double ue = a * (z0 - zt) * (z0 - zt);
    if (!(a > 0.0) || !(ue <= 0.5) || std::abs(zt - z0) > 4.0 * (z1 - z0)) return false;
    edge = i + 0.5 + dir * ue;
    tangentDepth = float(zt);
    return true;
  }

  // An end of pixel i toward an empty pixel at i + dir (the source's
  // silhouette) where the source sampled its outline finer: at the
  // outermost covered sample's edge and at that sample's depth, a point of
  // the surface by the silhouette, instead of the pixel's boundary at the
  // centre's depth. The boundary stands up to half a pixel outside the
  // surface, and its track, moving with the centre's depth, leaves the
  // outline as the view moves: a view next to the source drew the bunny's
  // outline one pixel wide at 39 pixels (issue 18). `depth`: the nearest
  // layer's, whose empty pixels make the silhouette. A layer behind it
  // ends on the same ray, kBehindOutline of the way from the silhouette's
  // point to its own depth: at the point itself (where a closed surface's
  // back meets its front) it ties with the nearest layer's slice and wins
  // half the depth tests there (the teacup's dark inner wall showed through
  // the rim: 35.5 against 37.0 dB mean), at its own depth it stands outside
  // the surface as the boundary did. 0.5 to 0.75 measured alike.
  static constexpr float kBehindOutline = 0.75f;
  // A layer behind the nearest ends kBehindInset inside its pixels at the
  // front's outline (on the ray that grazes the silhouette, a point behind
  // the front's lies outside the object, and so does its track in other
  // views; the outline may also lie beyond the pixel, PixelOutline) and at
  // its own depth steps (a surface seen steeply behind another, whose
  // footprint's ends leave it). Their tracks stood out of other views'
  // outlines: bunny 160x120, 31.3 -> 31.6 dB (sRGB); half a pixel in at
  // the outline, less. Toward its own holes it keeps the boundary: the
  // surface goes on there in a nearer layer (the box behind the thin bars,
  // inset there too: bunny 31.8 dB, thin-deep 22.1 -> 21.2, holes 16 ->
  // 140 a view).
  static constexpr double kBehindInset = 0.25;
  void insetBehind(const float* depth, int x, int n, float slope, const bool (&onOutline)[2], double (&ends)[2],
                   float (&d)[2], bool (&moved)[2]) const {
    const auto inset = float(kBehindInset);
    if (onOutline[0]) {
      ends[0] = std::max(ends[0], x + kBehindInset);
    } else if (x > 0 && depth[x - 1] != 0.0f && !joined(depth, x, x - 1)) {
      ends[0] = x + kBehindInset, d[0] += inset * slope, moved[0] = true;
    }
    if (onOutline[1]) {
      ends[1] = std::min(ends[1], x + n - kBehindInset);
    } else if (x + n < cam_.width() && depth[x + n] != 0.0f && !joined(depth, x + n - 1, x + n)) {
      ends[1] = x + n - kBehindInset, d[1] -= inset * slope, moved[1] = true;
    }
  }
  // `d`: the end's own depth on entry. A layer behind the front (`behind`)
  // ends kBehindOutline of the way from the front's silhouette point to
  // that depth, unless that point is another object's (far enough in depth
  // that the end's track would part from its own by more than a pixel):
  // an end between the two stretches the slice, so it keeps its own
  // (bunny 160x120: 32.2 -> 32.3 dB).
  bool outlineEnd(const PixelOutline& o, const float* depth, int i, int dir, bool behind, double& end,
                  float& d) const {
    if (!outlineRead(depth, cam_.width(), i, dir) || o.right < 0.0f) return false;
    float at = dir < 0 ? o.leftDepth : o.rightDepth;
    if (behind) {
      at += kBehindOutline * (d - at);
      if (std::abs(at - d) > 2.0f * join_) return false;
    }
    end = i + double(dir < 0 ? o.left : o.right);
    d = at;
    return true;
  }

  // The overlap toward pixel `to` from the run's end pixel `from`: only
  // beyond the image's edge, where the surface may go on; a joined side
  // meets its neighbour's slice instead (addRun).
  float widening(int to) const { return to < 0 || to >= cam_.width() ? options_.overlap : 0.0f; }

  bool joined(const float* depth, int from, int to) const {
    return to >= 0 && to < cam_.width() && depth[to] != 0.0f && std::abs(depth[from] - depth[to]) <= join_;
  }

  // A lone pixel's depth slope along the scanline, the central difference
  // of its neighbours where both continue its surface: its footprint then
  // lies on the surface's tangent, so a pixel the source sees frontally
  // shrinks where another view grazes the surface instead of standing out
  // of the silhouette at its full width. Between two covered neighbours
  // too far in depth to be joined, on a profile that rises or falls
  // through it, the gentler of its two one-sided slopes (a minmod
  // limiter): a surface the source sees steeply (a back layer near the
  // rim) then keeps its footprints on it, where flat ones stood out of
  // other views' outlines (bunny, 160x120: 26.5 -> 27.7 dB with this
  // alone), while a true step (one side flat) keeps them flat. A pixel at
  // a silhouette stays flat: extrapolated along a grazing tangent, its
  // outer end would leave the surface.
  float surfaceSlope(const float* depth, int x) const {
    if (joined(depth, x, x - 1) && joined(depth, x, x + 1)) return 0.5f * (depth[x + 1] - depth[x - 1]);
    if (x < 1 || x + 1 >= cam_.width() || depth[x - 1] == 0.0f || depth[x + 1] == 0.0f) return 0.0f;
    const float a = depth[x] - depth[x - 1], b = depth[x + 1] - depth[x];
    if (!(a * b > 0.0f)) return 0.0f;
    return std::abs(a) < std::abs(b) ? a : b;
  }

  // Where the other source sees nothing, nothing may be drawn in its view:
  // its front layer's coverage is exact there. The ends of a slice that
  // would cover, in that view, pixel centres the other source leaves empty
  // slide along their own rays (their x in this source fixed, their depth
  // changed) until the slice stops at the other source's outline, so
  // silhouettes move between the two sources' outlines instead of riding
  // fixed points (a contour slides over the surface as the eye moves).
  // Moves of more than a pixel are left alone: a real surface point lies
  // inside every view's outline, its footprint at most half a pixel out.
  // Only where the source has no finer outline: with one, its silhouette
  // ends are surface points already, and the slides of the others made
  // chords of the outline's curve across the track that stood outside it
  // in the middle views (teacup 640x480 x 100, dual: 40.6 -> 42.4 dB
  // without them; bunny 160x120 31.2 -> 31.3).
  void meetOtherOutline(const SourceLayer& layer, int j, const double (&x)[2], float (&d)[2]) const {
    const int w = cam_.width();
    const float* theirs = other_->depth.data() + size_t(j) * w;
    // A point at pixel x and window depth d of this source lands at
    // x + delta Z/w(d) in the other's view; Z/w is affine in d (GpuImageSlicer's
    // uZOverW: the same arithmetic, in double, on both back ends).
    const CameraSpec& s = cam_.spec();
    const double zx = s.distance * (s.farDistance - s.nearDistance) / (s.nearDistance * s.farDistance);
    const double zy = s.distance / s.farDistance - 1.0;
    const double perPlane = w / cam_.planeWidth(), left = cam_.viewX(0);
    const double delta = (layer.eye.x - left) * perPlane - (other_->eye.x - left) * perPlane;
    if (delta == 0.0) return;
    const double at[2] = {x[0] + delta * (zx * double(d[0]) + zy), x[1] + delta * (zx * double(d[1]) + zy)};
    const double l = at[0], r = at[1];
    if (!(r > l)) return;
    auto covered = [&](int i) { return i >= 0 && i < w && theirs[i] != 0.0f; };
    // The pixels whose centres the slice covers there: (l, r).
    const int first = int(std::ceil(l - 0.5)), last = int(std::ceil(r - 0.5)) - 1;
    int a = first, b = last;
    while (a <= b && !covered(a)) ++a;
    while (b >= a && !covered(b)) --b;
    double target[2] = {a > first ? double(a) : l, b < last ? double(b + 1) : r};
    if (a > b) {  // only empty pixels of theirs: pulled back to the outline beside, or gone there
      if (covered(first - 1)) target[0] = l, target[1] = std::max(l, double(first));
      else if (covered(last + 1)) target[0] = std::min(r, double(last + 1)), target[1] = r;
      else target[0] = target[1] = std::floor(0.5 * (l + r) + 0.5);  // a pixel edge: no centre covered
    }
    for (int e = 0; e < 2; ++e) {
      if (target[e] == at[e] || std::abs(target[e] - at[e]) > 1.0) continue;
      const double moved = ((target[e] - x[e]) / delta - zy) / zx;
      if (moved > 0.0 && moved <= 1.0) d[e] = float(moved);
    }
  }

  static uint32_t materialOf(const glm::vec4& normal) { return uint32_t(std::max(0.0f, normal.w) + 0.5f); }

  const ShearingCamera& cam_;
  const ImageSliceOptions& options_;
  ImageSlices& out_;
  ExtremeTransform transform_;
  std::optional<HighlightSplitter> highlights_;
  std::vector<glm::vec4> texels_;
  float join_ = 0.0f;  // the layer's depth step between neighbours of one surface
  const SourceLayer* other_ = nullptr;
  const SourceLayer* outlined_ = nullptr;  // the nearest layer of the source, where it has an outline
};

}  // namespace

std::vector<int> nearestLayerOf(const std::vector<glm::dvec2>& eyes) {
  std::vector<int> front(eyes.size());
  for (size_t k = 0; k < eyes.size(); ++k) front[k] = k > 0 && eyes[k - 1] == eyes[k] ? front[k - 1] : int(k);
  return front;
}

std::vector<int> nearestOtherSource(const std::vector<glm::dvec2>& eyes, const std::vector<uint8_t>& candidates) {
  std::vector<int> other(eyes.size(), -1);
  const std::vector<int> nearestLayer = nearestLayerOf(eyes);
  for (size_t k = 0; k < eyes.size(); ++k) {
    double nearest = INFINITY;
    for (size_t m = 0; m < eyes.size(); ++m) {
      const double apart = glm::length(eyes[m] - eyes[k]);
      const bool front = nearestLayer[m] == int(m) && (candidates.empty() || candidates[m]);
      if (front && apart > 0.0 && apart < nearest) nearest = apart, other[k] = int(m);
    }
  }
  return other;
}

float coalesceDepthRange(const ShearingCamera& cam, double eyeX, float pixels) {
  const TrackParallax parallax(cam);
  const double pixelsPerDepth = parallax.reach(eyeX) * parallax.pixelsPerDepth();
  return pixelsPerDepth > 0.0 ? float(pixels / pixelsPerDepth) : std::numeric_limits<float>::infinity();
}

ImageSlices sliceSourceLayers(const std::vector<SourceLayer>& layers, const ShearingCamera& cam,
                              int row, const ImageSliceOptions& options) {
  const int w = cam.width(), h = cam.height();
  for (const SourceLayer& layer : layers)
    if (layer.color.width != w || layer.color.height != h || layer.color.type != PixelType::F32 ||
        layer.depth.size() != size_t(w) * h)
      fail("sliceSourceLayers", "source layers must be float images of the output size");
  // Each band holds its scanlines' slices of every layer, layer by layer,
  // so joined in band order each scanline lists them as one pass would.
  std::vector<glm::dvec2> eyes;
  for (const SourceLayer& layer : layers) eyes.push_back(layer.eye);
  const std::vector<int> other = nearestOtherSource(eyes), front = nearestLayerOf(eyes);
  const int bandRows = std::max(1, options.bandRows), bands = (h + bandRows - 1) / bandRows;
  std::vector<ImageSlices> parts(size_t(std::max(1, bands)));
  std::vector<std::vector<uint32_t>> scanlines(parts.size());
  std::vector<std::vector<uint32_t>> layerOf(parts.size());
  parallelFor(0, bands, [&](int b) {
    const int first = b * bandRows, last = std::min(h, (b + 1) * bandRows);
    // At most a slice per covered pixel: reserved, the arrays never copy
    // as they grow (growing, slicing was bound by copies and page faults).
    size_t covered = 0;
    for (const SourceLayer& layer : layers)
      covered += size_t(std::count_if(layer.depth.begin() + size_t(first) * w, layer.depth.begin() + size_t(last) * w,
                                      [](float d) { return d != 0.0f; }));
    parts[b].vertices.reserve(2 * covered, covered, 2 * covered);
    LayerSlicer slicer(cam, row, options, parts[b]);
    slicer.scanlineOf.reserve(covered);
    for (size_t k = 0; k < layers.size(); ++k) {
      slicer.slice(layers[k], first, last, options.meetSilhouettes && other[k] >= 0 ? &layers[other[k]] : nullptr,
                   &layers[front[k]]);
      layerOf[b].resize(slicer.scanlineOf.size(), uint32_t(k));
    }
    scanlines[b] = std::move(slicer.scanlineOf);
  });
  // Joined into room reserved for all: each array copied once.
  ImageSlices out;
  size_t vertices = 0, triangles = 0, texels = 0;
  for (const ImageSlices& part : parts) {
    vertices += part.vertices.vertexCount(), triangles += part.vertices.triangles.size();
    texels += part.vertices.vectorTexels.texels().size();
  }
  out.vertices.reserve(vertices, triangles, texels);
  std::vector<uint32_t> scanlineOf;
  scanlineOf.reserve(triangles);
  for (size_t b = 0; b < parts.size(); ++b) {
    appendVertices(out.vertices, parts[b].vertices);
    out.pixels += parts[b].pixels;
    scanlineOf.insert(scanlineOf.end(), scanlines[b].begin(), scanlines[b].end());
    out.layerOf.insert(out.layerOf.end(), layerOf[b].begin(), layerOf[b].end());
  }
  out.vertices.cullBack.assign(out.vertices.triangles.size(), 0);
  out.vertices.materials.assign(out.vertices.triangles.size(), 0);
  out.table = SliceTable::fromSegments(scanlineOf, h);
  return out;
}

}  // namespace mvr
