// The CPU back end (Halle's span pseudocode): for every PST and every view
// row it crosses, one exact horizontal span. It is the test oracle and the
// renderer for machines without a GPU. Scanlines are independent, so
// the pool's workers take whole scanlines; frames leave in scanline order.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "epi/epi_rasterizer.h"
#include "epi/diffuse_spans.h"
#include "epi/epi_batch.h"
#include "epi/pst.h"
#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/parallel.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {

using namespace spans;  // epi/diffuse_spans.h: the fill's vector helpers

class SpanRasterizer final : public EpiRasterizer {
 public:
  SpanRasterizer(PixelType type, const EpiShading& shading, SpanPaths paths)
      : type_(type), shading_(shading), paths_(paths) {
#if MVR_SPAN_V2
    v2_ = !paths.baselineIsa && __builtin_cpu_supports("x86-64-v2");
#endif
    if (type_ == PixelType::U8) thresholds_ = thresholdsOf([](float v) { return int(std::lrint(v * 255.0f)); });
    if (type_ == PixelType::Srgb8) thresholds_ = thresholdsOf([this](float v) { return int(srgb8_(v)); });
    if (shading_.plan.passes().size() > 1 && !shading_.scene && !shading_.sliceVectors)
      fail("cpu rasterizer", "shading passes need a scene");
    if (shading_.plan.texture && !shading_.textures) fail("cpu rasterizer", "texturing needs textures");
    if (shading_.plan.reflection && !shading_.environment)
      fail("cpu rasterizer", "reflection needs the reflection maps");
  }

  using EpiRasterizer::rasterize;
  void rasterize(const ExtremeVertices& v, const SliceTableView& slices, const ShearingCamera& cam,
                 int row, FrameSink& sink, RenderStats& stats) override {
    const SliceTable& table = slices.host();  // spans are walked on the CPU
    const IndexRange lines = cam.share().scanlines;
    eye0_ = glm::vec3(cam.eye(0, row));
    eyeStep_ = glm::vec3(cam.eye(1, row) - cam.eye(0, row));
    ScopedStage s(stats.times, "raster");  // with the hand-over beside it
    fillEpisInOrder(sink, row, lines, cam.width(), cam.views(), type_, ring_, [&](int j, const PixelRows& epi) {
      thread_local std::vector<float> depth;  // a worker's scratch, reused across EPIs
      fillEpi(v, table, cam, j, epi, depth);
    });
  }

 private:
  void fillEpi(const ExtremeVertices& v, const SliceTable& table, const ShearingCamera& cam, int j,
               const PixelRows& epi, std::vector<float>& depth) const {
    const int w = cam.width(), n = cam.views();
    std::memset(epi.data, 0, epi.bytes());
    depth.assign(size_t(w) * n + 3, 0.0f);  // reversed Z: 0 is far; 3 floats for plainRun's last lanes
    for (const Slice& s : table.scanline(j)) {
      auto [e0, e1] = sliceEnds(v, s);
      const Pst pst = makePst(e0, e1, n, v.cullBack[s.triangle]);
      const uint32_t material = v.materials.empty() ? 0 : v.materials[s.triangle];
      const SliceVector* vector = shading_.sliceVectors ? &v.vectors.at(s.triangle) : nullptr;
      for (int p = 0; p < pst.pieceCount; ++p)
        fillPiece(pst, pst.pieces[p], material,
                  vector ? Colors{&v.vectorTexels, vector, v.knots.data()} : Colors{}, epi, depth);
    }
  }

  template <size_t N>
  using Bytes = std::integral_constant<size_t, N>;  // a pixel's, known to the compiler

  // Where a slice's colour comes from: its vertices, or its own vector.
  struct Colors {
    const shading::TextureVectors* texels = nullptr;
    const SliceVector* vector = nullptr;
    const HighlightKnot* knots = nullptr;
  };

  // A split track's highlight at row coordinate r: linear between knots.
  static glm::vec3 highlight(const HighlightKnot* knots, int count, float r) {
    if (count < 2) return glm::vec3(0.0f);
    int k = 0;
    while (k + 2 < count && knots[k + 1].r <= r) ++k;
    const float span = knots[k + 1].r - knots[k].r;
    const float t = span > 0.0f ? std::clamp((r - knots[k].r) / span, 0.0f, 1.0f) : 0.0f;
    return glm::mix(knots[k].specular, knots[k + 1].specular, t);
  }

  // Row i's span: the slice's first end xa, the signed width to its
  // second, and the two ends in order, [lo, hi). Each end is its edge's
  // own value at the row, never xa + width (which rounds): two slices that
  // share an edge then test a centre on it against the same float, and
  // exactly one of them keeps it (no crack along a seam through centres).
  struct RowSpan {
    float xa, width, lo, hi;
  };
  static RowSpan rowSpan(const Pst& pst, int i) {
    const float r = i + 0.5f;
    const float xa = pst.x0(r), xb = pst.x1(r);
    return {xa, xb - xa, std::min(xa, xb), std::max(xa, xb)};
  }

  // The pixel columns a piece's rows [iFirst, iLast) can reach, and how
  // far (in pixels) the rounded edges may stray from the exact lines.
  struct Columns {
    int begin = 0, end = 0;
    float slack = 0.0f;
  };
  static Columns columnsOf(const Pst& pst, int iFirst, int iLast, int w) {
    const float ends[4] = {pst.x0(iFirst + 0.5f), pst.x0(iLast - 0.5f), pst.x1(iFirst + 0.5f), pst.x1(iLast - 0.5f)};
    float lo = ends[0], hi = ends[0], size = 0.0f;
    for (float e : ends) lo = std::min(lo, e), hi = std::max(hi, e), size = std::max(size, std::abs(e));
    size = std::max({size, std::abs(pst.e0.x0), std::abs(pst.e1.x0)});
    // A few float steps of the largest magnitude the edges pass through.
    const float slack = 1e-3f + 1e-5f * size;
    lo = std::clamp(lo, -1e9f, 1e9f), hi = std::clamp(hi, -1e9f, 1e9f);  // far corners: no int overflow
    return {std::max(0, int(std::floor(lo)) - 1), std::min(w, int(hi) + 2), slack};
  }

  // The column walk tests about (area + a few rows per column) pixels; the
  // row walk pays a row's ends for each of its rows and then only fills.
  // The piece's area is its rows times its mean width (linear in r).
  static bool byColumns(const Pst& pst, int iFirst, int iLast, const Columns& columns) {
    const int rows = iLast - iFirst;
    const float meanWidth = 0.5f * (std::abs(pst.width(iFirst + 0.5f)) + std::abs(pst.width(iLast - 0.5f)));
    return float(rows) * meanWidth + 3.0f * float(columns.end - columns.begin) < float(rows);
  }

  // The rows of [iFirst, iLast) where centre c may lie between the two
  // edges, a superset of those where it does: for each order of the
  // edges, the rows where one is at most c and the other above it (each a
  // half-line of rows), widened by `slack` pixels and a row.
  static std::pair<int, int> rowsHolding(const Pst& pst, float c, int iFirst, int iLast, float slack) {
    // Row i's edge is x0 + i dx (r - 0.5 = i).
    const float e[2] = {pst.e0.x0, pst.e1.x0}, d[2] = {pst.e0.dx, pst.e1.dx};
    auto rows = [&](int k, bool atMost) -> std::pair<int, int> {
      const float bound = atMost ? c + slack : c - slack;
      if (d[k] == 0) return (atMost ? e[k] <= bound : e[k] > bound) ? std::pair(iFirst, iLast) : std::pair(0, 0);
      const double t = std::clamp((double(bound) - e[k]) / d[k], double(iFirst) - 4, double(iLast) + 4);
      // e + i d <= bound: i <= t when d > 0, i >= t when d < 0.
      const bool upTo = (d[k] > 0) == atMost;
      return upTo ? std::pair(iFirst, std::min(iLast, int(std::floor(t)) + 2))
                  : std::pair(std::max(iFirst, int(std::ceil(t)) - 1), iLast);
    };
    int first = iLast, last = iFirst;
    for (int k = 0; k < 2; ++k) {
      const auto [a0, a1] = rows(k, true);
      const auto [b0, b1] = rows(1 - k, false);
      const int lo = std::max(a0, b0), hi = std::min(a1, b1);
      if (lo < hi) first = std::min(first, lo), last = std::max(last, hi);
    }
    return {first, last};
  }

  // A piece is walked by rows (a span per view) or, when it is narrower
  // than a pixel on most rows, by columns (the views whose span holds the
  // pixel): a PST of the 143K teacup at 160x140 x 1000 views crosses 1000
  // rows and a few dozen columns, and most of its rows hold no pixel.
  // Both walks test each pixel with the same fill rule, so they fill the
  // same pixels. Untextured, diffuse slices (the common case) are filled
  // four pixels at a time (plainRun) with the same arithmetic in every
  // lane, so they get the same bytes as the general path.
  void fillPiece(const Pst& pst, const PstPiece& piece, uint32_t material, Colors colors, const PixelRows& epi,
                 std::vector<float>& depth) const {
#if MVR_SPAN_V2
    // The stream at 640x480 x 1000 views: 8% faster than the baseline code.
    if (v2_) return fillPieceV2(pst, piece, material, colors, epi, depth);
#endif
    fillPieceOn(pst, piece, material, colors, epi, depth);
  }
#if MVR_SPAN_V2
  [[gnu::target("arch=x86-64-v2")]] void fillPieceV2(const Pst& pst, const PstPiece& piece, uint32_t material,
                                                     Colors colors, const PixelRows& epi,
                                                     std::vector<float>& depth) const {
    fillPieceOn(pst, piece, material, colors, epi, depth);
  }
#endif
  [[gnu::always_inline]] void fillPieceOn(const Pst& pst, const PstPiece& piece, uint32_t material, Colors colors,
                                          const PixelRows& epi, std::vector<float>& depth) const {
    const shading::ShadingPlan& plan = shading_.plan;
    const int w = epi.width;
    // A vector of one texel and no highlight (interp's slice of a source
    // pixel) has vectorColor's value at any u, view and width: that texel.
    const bool oneTexel = colors.vector && colors.vector->length == 1 && colors.vector->knotCount == 0 &&
                          type_ != PixelType::F32;
    if ((colors.vector && !oneTexel) || plan.uv >= 0 || plan.position >= 0 || !paths_.fastDiffuse) {
      const float cutoff = plan.mask && !colors.vector ? alphaCutoff(material) : 0.0f;
      const int cutLayer = cutoff > 0.0f ? shading_.textures->materialLayers()[material] : -1;
      auto run = [&](int i, int x0, int x1, float xa, float width) {
        float* dz = depth.data() + size_t(i) * w;
        for (int x = x0; x < x1; ++x) {
          const float u = std::clamp((x + 0.5f - xa) / width, 0.0f, 1.0f);
          const float z = pstDepth(pst, u);
          if (!(z > dz[x])) continue;
          if (cutoff > 0.0f && texel(pst, cutLayer, u, 1.0f / width).a < cutoff) continue;  // cut out
          dz[x] = z;
          store(epi, x, i, colors.vector ? vectorColor(colors, u, width, i)
                                         : shade(pst, piece.front, material, u, 1.0f / width, float(i)));
        }
      };
      walkPiece(pst, piece, w, epi.height, paths_.walk, run,
                [&](int i, int x, float xa, float width) { run(i, x, x + 1, xa, width); });
      return;
    }
    // Inlined, so that the fill is compiled for each instruction set
    // (MVR_SPAN_V2); 8-bit codes only for 4-byte pixels.
    auto plain = [&](auto encode, auto bytes) __attribute__((always_inline)) {
      constexpr size_t pixelBytes = decltype(bytes)::value;
      const PlainSlice slice(pst, piece.front);
      SliceCodes codes;
      if constexpr (pixelBytes == 4) {
        if (oneTexel) {
          codes.kind = SliceCodes::Kind::Flat;
          encode(codes.pixel.data(), glm::clamp(vectorColor(colors, 0.0f, 1.0f, 0), 0.0f, 1.0f));
        } else {
          codes = sliceCodes(pst, piece.front, encode, thresholds_);
        }
      }
      const bool flat = codes.kind == SliceCodes::Kind::Flat;
      walkPiece(
          pst, piece, w, epi.height, paths_.walk,
          [&](int i, int x0, int x1, float xa, float width) {
            plainRun(slice, codes, depth.data() + size_t(i) * w, epi.row(i), w, pixelBytes, x0, x1, xa, width, encode);
          },
          [&](int i, int x, float xa, float width) {  // one lane is cheaper alone
            const float u = std::clamp((x + 0.5f - xa) / width, 0.0f, 1.0f);
            const float z = pstDepth(pst, u);
            float& dz = depth[size_t(i) * w + x];
            if (!(z > dz)) return;
            dz = z;
            uint8_t* p = epi.row(i) + size_t(x) * pixelBytes;
            if (flat) std::memcpy(p, codes.pixel.data(), 4);
            else encode(p, clampFor(pstColor(pst, piece.front, u)));
          });
    };
    switch (type_) {
      case PixelType::U8: return plain([](uint8_t* p, const glm::vec3& c) { storeU8(p, c); }, Bytes<4>{});
      case PixelType::Srgb8: return plain([this](uint8_t* p, const glm::vec3& c) { storeSrgb8(p, c); }, Bytes<4>{});
      default: return plain([](uint8_t* p, const glm::vec3& c) { storeF32(p, c); }, Bytes<16>{});
    }
  }

  // Calls run(i, x0, x1, xa, width) for pixels x0 <= x < x1 of row i, all
  // inside the piece's span there (which starts at xa, signed width), and
  // pixel(i, x, xa, width) for single pixels of the column walk.
  template <class Run, class Pixel>
  [[gnu::always_inline]] static void walkPiece(const Pst& pst, const PstPiece& piece, int w, int n,
                                               SpanPaths::Walk walk, Run&& run,
                                               Pixel&& pixel) {
    // Views whose row centre i + 0.5 lies in [rTop, rBottom).
    const int iFirst = std::max(0, ceilToInt(piece.rTop - 0.5f));
    const int iLast = std::min(n, ceilToInt(piece.rBottom - 0.5f));
    if (iFirst >= iLast) return;
    // The fill rule: pixel x is in row i's span when its centre lies in
    // [lo, hi) (ceil(lo - 0.5) <= x < ceil(hi - 0.5)).
    const Columns columns = columnsOf(pst, iFirst, iLast, w);
    const bool columnwise = walk == SpanPaths::Walk::Auto ? byColumns(pst, iFirst, iLast, columns)
                                                          : walk == SpanPaths::Walk::Columns;
    if (!columnwise) {
      // rowSpan() and the fill rule for four rows at a time.
      const I4 lanes = {0, 1, 2, 3};
      for (int i = iFirst; i < iLast; i += 4) {
        const F4 r = __builtin_convertvector(i + lanes, F4) + 0.5f;
        const F4 xa = pst.e0.x0 + (r - 0.5f) * pst.e0.dx, xb = pst.e1.x0 + (r - 0.5f) * pst.e1.dx;
        const F4 width = xb - xa;  // the ends as rowSpan() has them
        const I4 first = ceilToInt((xb < xa ? xb : xa) - 0.5f), last = ceilToInt((xa < xb ? xb : xa) - 0.5f);
        for (int k = 0; k < std::min(4, iLast - i); ++k)
          if (width[k] != 0) run(i + k, std::max(0, first[k]), std::min(w, last[k]), xa[k], width[k]);
      }
      return;
    }
    for (int x = columns.begin; x < columns.end; ++x) {
      const auto [first, last] = rowsHolding(pst, x + 0.5f, iFirst, iLast, columns.slack);
      for (int i = first; i < last; ++i) {
        const RowSpan s = rowSpan(pst, i);
        if (s.width != 0 && s.lo - 0.5f <= float(x) && float(x) < s.hi - 0.5f) pixel(i, x, s.xa, s.width);
      }
    }
  }

  // Every pass of the plan at once, in the order the GL passes accumulate.
  // du: the change of u over one pixel of this view (texture footprint).
  glm::vec3 shade(const Pst& pst, bool front, uint32_t material, float u, float du, float view) const {
    glm::vec3 color = pstColor(pst, front, u);
    const shading::ShadingPlan& plan = shading_.plan;
    glm::vec3 t(1.0f);
    if (plan.uv >= 0) {
      // The lit colour carries the emission, unless it has a texture; the
      // multiply must not dim it.
      t = glm::vec3(texel(pst, shading_.textures->materialLayers()[material], u, du));
      const glm::vec3 e = shading_.scene->materials[material].emission;
      color *= t;
      if (const int glow = shading_.textures->emissionLayers()[material]; glow >= 0)
        color += e * glm::vec3(texel(pst, glow, u, du));
      else if (plan.emission)
        color += e * (1.0f - t);
    }
    if (plan.position < 0) return color;
    const glm::vec3 p = pstExtras<3>(pst, plan.position, u);
    const glm::vec3 n = pstExtras<3>(pst, plan.normal, u) * (front ? 1.0f : -1.0f);
    const glm::vec3 eye = eye0_ + view * eyeStep_;
    const Material& m = shading_.scene->materials[material];
    const glm::vec3 albedo = plan.albedo >= 0 ? pstExtras<3>(pst, plan.albedo, u) * t : glm::vec3(0.0f);
    const shading::ViewDependentLight light = shading::viewDependentLight(*shading_.scene, m, albedo, p, n, eye);
    color += light.specular;
    if (plan.albedo >= 0) color -= light.fresnelLoss;
    if (plan.reflect >= 0) {
      float affine[9];
      pstExtras(pst, plan.reflect, 9, u, affine);
      const glm::vec3 r = shading::reflectionVector(affine, eye);
      const glm::vec3 reflectivity = shading_.scene->materials[material].reflectivity;
      color += reflectivity * shading_.environment->sample(shading_.environment->materialMaps()[material], r);
    }
    return color;
  }

  // A texture layer at the exact perspective-correct uv; level of detail
  // from the horizontal footprint, as the GL direct path.
  glm::vec4 texel(const Pst& pst, int layer, float u, float du) const {
    if (layer < 0) return glm::vec4(1.0f);
    const int at = shading_.plan.uv;
    const glm::vec2 uv = pstExtras<2>(pst, at, u), next = pstExtras<2>(pst, at, u + du);
    return shading_.textures->sample(layer, uv, shading_.textures->lodFor(layer, next - uv));
  }

  // A cut-out material's alpha cut-off; 0 for an opaque one.
  float alphaCutoff(uint32_t material) const {
    const Material& m = shading_.scene->materials[material];
    return m.masked() ? m.alphaCutoff : 0.0f;
  }

  // A slice with a texture vector: its texel at u, and the highlight of
  // view i when its track was split.
  static glm::vec3 vectorColor(const Colors& colors, float u, float width, int i) {
    const SliceVector& sv = *colors.vector;
    const float t = sv.u0 + (sv.u1 - sv.u0) * u, perPixel = sv.length * std::abs((sv.u1 - sv.u0) / width);
    const glm::vec3 c(colors.texels->sample(sv.base, sv.length, t, perPixel));
    return c + highlight(colors.knots + sv.firstKnot, sv.knotCount, i + 0.5f);
  }

  // What a pixel of the target's type holds: [0, 1] in 8 bits; float
  // keeps HDR radiance above 1 (EXR, --tonemap), as the GL targets do.
  glm::vec3 clampFor(const glm::vec3& c) const {
    return type_ == PixelType::F32 ? glm::max(c, 0.0f) : glm::clamp(c, 0.0f, 1.0f);
  }

  void store(const PixelRows& img, int x, int y, const glm::vec3& c) const {
    const glm::vec3 v = clampFor(c);
    uint8_t* p = img.row(y) + size_t(x) * 4 * (type_ == PixelType::F32 ? 4 : 1);
    if (type_ == PixelType::U8) storeU8(p, v);
    else if (type_ == PixelType::Srgb8) storeSrgb8(p, v);
    else storeF32(p, v);
  }
  // v in [0, 1]. GL's float -> unorm8 conversion: round to nearest.
  static void storeU8(uint8_t* p, const glm::vec3& v) {
    p[0] = uint8_t(std::lrint(v.r * 255.0f));
    p[1] = uint8_t(std::lrint(v.g * 255.0f));
    p[2] = uint8_t(std::lrint(v.b * 255.0f));
    p[3] = 255;
  }
  void storeSrgb8(uint8_t* p, const glm::vec3& v) const {
    p[0] = srgb8_(v.r), p[1] = srgb8_(v.g), p[2] = srgb8_(v.b), p[3] = 255;
  }
  static void storeF32(uint8_t* bytes, const glm::vec3& v) {
    float* p = reinterpret_cast<float*>(bytes);
    p[0] = v.r, p[1] = v.g, p[2] = v.b, p[3] = 1.0f;
  }

  PixelType type_;
  std::vector<Image> ring_;  // EPIs being filled and handed on, reused
  Srgb8Encoder srgb8_;
  EpiShading shading_;
  SpanPaths paths_;
  std::array<float, 255> thresholds_{};  // of the 8-bit pixel type's encoding
  glm::vec3 eye0_{0.0f}, eyeStep_{0.0f};
  bool v2_ = false;  // fill with the x86-64-v2 code
};

}  // namespace

std::unique_ptr<EpiRasterizer> makeSpanRasterizer(PixelType type, const EpiShading& shading, SpanPaths paths) {
  return std::make_unique<SpanRasterizer>(type, shading, paths);
}

}  // namespace mvr
