// The CPU span rasterizer's rule (epi/span_rasterizer.cpp) in compute
// shaders: no GL rasterization. On GPUs built for compute the graphics
// pipeline is a small part of the chip (an H100 runs vertex and fragment
// shaders on 2 of its 66 TPCs), and PSTs, a pixel or two wide and a whole
// track tall, are the worst shape for it: 287K PSTs into 640x1000 EPIs
// took the H100's rasterizer 139 ms of GPU time.
//
// Per batch of scanlines, a first pass finds every slice's track (its ends
// and pieces). Then a work group owns a tile of one EPI (columns x view
// rows) in on-chip memory and walks the scanline's slices, a thread per
// slice and a span per row, twice: the nearest depth of every pixel (atomic
// max of the float's bits: depth is reversed, in (0, 1]); then the first
// slice in table order that reaches it (atomic min of the slice's index),
// which is the CPU's "strictly nearer replaces" rule. Last, each pixel's
// winner is shaded once. Tiles are written to a storage buffer in the
// stacked-EPI layout and copied into the readback ring; or, where the sink
// lends a texture (FrameSink::epiTexture: mvr live's screen), straight
// into its layers, and nothing is read back.
#include <algorithm>
#include <array>
#include <optional>

#include "epi/epi_batch.h"
#include "epi/epi_rasterizer.h"
#include "epi/gpu/pst_geometry.h"
#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/gpu_clock.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/image_pool.h"
#include "shading/texture_vector.h"

namespace mvr {
namespace {

// What both passes know of a slice's track: its ends' x0 and dx, their
// depths and 1/w, and its pieces (pstPieces: piece 0 in rows.xy, the one
// past the edge-on view in rows.zw) as rows of views [begin, end) with the
// piece's facing in bit 31 of end; a piece not drawn has no rows.
const char* const kTrack = R"(
struct Track { vec4 x; vec4 d; uvec4 rows; };
layout(std430, binding = 7) buffer Tracks { Track uTracks[]; };
)";

// Per slice of the batch, once: the ends' records interpolated and the
// pieces found here, so that the tile pass's two walks over the slices
// compute each fragment's depth from the same floats.
const char* const kTrackPass = R"(
layout(local_size_x = 64) in;
uniform uint uFirst, uCount;  // slices [uFirst, uFirst + uCount)
// Views whose row centre i + 0.5 lies in [top, bottom), with the facing
// in bit 31 of the end; none where the piece is not drawn.
uvec2 rowsOf(bool drawn, float top, float bottom, bool front) {
  if (!drawn) return uvec2(0u);
  uint begin = uint(max(0.0, ceil(top - 0.5))), end = uint(min(uViews, ceil(bottom - 0.5)));
  return uvec2(begin, end | (front ? 0x80000000u : 0u));
}
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  End e0, e1;
  uint word;
  sliceEnds(uFirst + i, e0, e1, word);
  PstPieces p = pstPieces(e0, e1, uViews, (word >> 31) != 0u);
  uvec4 rows = uvec4(rowsOf(p.drawn.x, p.top.x, p.bottom.x, p.front.x),
                     rowsOf(p.drawn.y, p.top.y, p.bottom.y, p.front.y));
  uTracks[uFirst + i] = Track(vec4(e0.x0, e0.dx, e1.x0, e1.dx), vec4(e0.depth, e1.depth, e0.invW, e1.invW), rows);
}
)";

// The tile pass; needs the slice library (PstGeometry::glslLibrary: End,
// sliceEnds) and kTrack. Arithmetic is the CPU's, term for term, and
// `precise` where a fused multiply-add would round otherwise; the GPU's
// division is within a few ulps of the CPU's, so a pixel may differ by a
// step where a span's end or a depth tie lands within that of a pixel
// centre.
const char* const kSpans = R"(
layout(local_size_x = 256) in;
layout(std430, binding = 5) readonly buffer Offsets { uint uOffsets[]; };
#if defined(IMAGE_OUT)
// The sink's RGBA8 layers, bound as 32-bit words: the bytes as packed.
layout(r32ui, binding = 0) writeonly uniform uimage2DArray uEpiLayers;
#elif defined(FLOAT_OUT)
layout(std430, binding = 6) writeonly buffer Epis { vec4 uEpis[]; };
#else
layout(std430, binding = 6) writeonly buffer Epis { uint uEpis[]; };
#endif
uniform int uFirstScanline;  // the batch's first; EPI k of the batch is work group z = k
uniform int uWidth;
uniform int uTileColumns, uTileRows;  // uTileColumns * uTileRows <= TILE
#ifdef SRGB
uniform float uSrgbUpper[255];  // mvr/color.h: byte b rounds up to b + 1 at uSrgbUpper[b]
#endif
shared uint sDepth[TILE];
shared uint sWinner[TILE];

int gX0, gXEnd, gI0, gIEnd;
uint gFirst;  // the scanline's first slice

// A row's span: its left end xa and width (pst.h's x0(r) and width(r)),
// and the tile's columns [x, y) whose centres it covers.
struct Span { float xa, width; ivec2 columns; };
Span spanAt(Track t, int i) {
  Span s;
  float r = float(i) + 0.5;
  precise float xa = t.x.x + (r - 0.5) * t.x.y, x1 = t.x.z + (r - 0.5) * t.x.w;
  precise float width = x1 - xa;
  s.xa = xa;
  s.width = width;
  // The ends themselves, not xa + width (as the CPU's rowSpan): no crack
  // along an edge two slices share.
  float lo = min(xa, x1), hi = max(xa, x1);
  // Clamped as floats: ends far outside the image stay representable.
  // A span of no width covers no centre, as the CPU's `width == 0` skip;
  // no test for it here: NVIDIA's compiler (580.159) evaluated
  // `if (!(width != 0.0))` as true for some slices of 0.01-0.03 px whose
  // stored width compared unequal to 0 (0.3% of a teacup's pixels lost).
  s.columns = ivec2(clamp(ceil(lo - 0.5), float(gX0), float(gXEnd)),
                    clamp(ceil(hi - 0.5), float(gX0), float(gXEnd)));
  return s;
}
float uAt(Span s, int x) {
  precise float u = (float(x) + 0.5 - s.xa) / s.width;
  return clamp(u, 0.0, 1.0);
}
float depthAt(Track t, float u) {
  precise float z = t.d.x + (t.d.y - t.d.x) * u;
  return z;
}
ivec2 pieceRows(Track t, int k) {
  uvec2 r = k == 0 ? t.rows.xy : t.rows.zw;
  return ivec2(r.x, r.y & 0x7FFFFFFFu);
}

// Phase 0: nearest depth per pixel; phase 1: first slice at that depth.
void visit(uint s, int phase) {
  Track t = uTracks[s];
  for (int k = 0; k < 2; ++k) {
    ivec2 rows = pieceRows(t, k);
    for (int i = max(rows.x, gI0); i < min(rows.y, gIEnd); ++i) {
      Span span = spanAt(t, i);
      int row = (i - gI0) * uTileColumns - gX0;
      for (int x = span.columns.x; x < span.columns.y; ++x) {
        float z = depthAt(t, uAt(span, x));
        if (!(z > 0.0)) continue;  // behind the cleared depth, or NaN
        uint at = uint(row + x), bits = floatBitsToUint(z);
        if (phase == 0) atomicMax(sDepth[at], bits);
        else if (sDepth[at] == bits) atomicMin(sWinner[at], s - gFirst);
      }
    }
  }
}

#ifdef VECTORS
// Image slices: each coloured by its own texture vector of source pixels,
// its parameter linear in u from u0 to u1 (the CPU spans' Colors path).
layout(std430, binding = 8) readonly buffer Vectors { uvec4 uVectors[]; };  // GpuVertices::vectors
layout(binding = 3) uniform samplerBuffer uVectorTexels;
vec4 shade(uint s, int i, int x) {
  Track t = uTracks[s];
  uvec4 v = uVectors[uSlices[s].x];
  float k = float(v.y), u0 = uintBitsToFloat(v.z), u1 = uintBitsToFloat(v.w);
  Span span = spanAt(t, i);
  float u = uAt(span, x);
  float perPixel = k * abs((u1 - u0) / span.width);
  vec4 c = k == 0.0 ? vec4(1.0) : sampleTextureVector(uVectorTexels, int(v.x), k, u0 + (u1 - u0) * u, perPixel);
  return vec4(clamp(c.rgb, 0.0, 1.0), 1.0);
}
#else
// The winner's colour: hyperbolic in u, as pstColor.
vec4 shade(uint s, int i, int x) {
  Track t = uTracks[s];
  End e0, e1;
  uint word;
  sliceEnds(s, e0, e1, word);
  bool second = i >= pieceRows(t, 1).x && i < pieceRows(t, 1).y;
  bool front = ((second ? t.rows.w : t.rows.y) & 0x80000000u) != 0u;
  float u = uAt(spanAt(t, i), x);
  int at = front ? 4 : 7;  // GpuVertices records: colour / w, front then back
  vec3 c0 = vec3(endAttribute(e0, at), endAttribute(e0, at + 1), endAttribute(e0, at + 2));
  vec3 c1 = vec3(endAttribute(e1, at), endAttribute(e1, at + 1), endAttribute(e1, at + 2));
  precise float invW = t.d.z + (t.d.w - t.d.z) * u;
  precise vec3 c = (c0 + (c1 - c0) * u) / invW;
  return vec4(clamp(c, 0.0, 1.0), 1.0);
}
#endif

#ifndef FLOAT_OUT
uint byteOf(float v) {
#ifdef SRGB
  int lo = 0, hi = 255;  // the number of thresholds at or below v
  while (lo < hi) {
    int mid = (lo + hi) >> 1;
    if (uSrgbUpper[mid] <= v) lo = mid + 1; else hi = mid;
  }
  return uint(lo);
#else
  return uint(roundEven(v * 255.0));
#endif
}
#endif

void main() {
  int views = int(uViews);
  gX0 = int(gl_WorkGroupID.x) * uTileColumns;
  gXEnd = min(uWidth, gX0 + uTileColumns);
  gI0 = int(gl_WorkGroupID.y) * uTileRows;
  gIEnd = min(views, gI0 + uTileRows);
  uint j = uint(uFirstScanline) + gl_WorkGroupID.z, tid = gl_LocalInvocationIndex;
  uint pixels = uint(uTileColumns * uTileRows);
  for (uint at = tid; at < pixels; at += 256u) { sDepth[at] = 0u; sWinner[at] = 0xFFFFFFFFu; }
  gFirst = uOffsets[j];
  uint last = uOffsets[j + 1u];
  memoryBarrierShared();
  barrier();
  for (uint s = gFirst + tid; s < last; s += 256u) visit(s, 0);
  memoryBarrierShared();
  barrier();
  for (uint s = gFirst + tid; s < last; s += 256u) visit(s, 1);
  memoryBarrierShared();
  barrier();
  for (uint at = tid; at < pixels; at += 256u) {
    int x = gX0 + int(at) % uTileColumns, i = gI0 + int(at) / uTileColumns;
    if (x >= gXEnd || i >= gIEnd) continue;
    uint winner = sWinner[at];
    vec4 c = winner == 0xFFFFFFFFu ? vec4(0.0) : shade(gFirst + winner, i, x);
    uint dst = (gl_WorkGroupID.z * uint(views) + uint(i)) * uint(uWidth) + uint(x);
#ifdef FLOAT_OUT
    uEpis[dst] = c;
#else
    uint word = winner == 0xFFFFFFFFu ? 0u : byteOf(c.r) | byteOf(c.g) << 8 | byteOf(c.b) << 16 | 255u << 24;
#ifdef IMAGE_OUT
    imageStore(uEpiLayers, ivec3(x, i, int(j)), uvec4(word));
#else
    uEpis[dst] = word;
#endif
#endif
  }
}
)";

// Storage for one batch's EPIs: each slot's bytes at most (the copy into
// the readback ring is as large).
size_t gBatchBytes = size_t(64) << 20;

size_t pixelBytes(PixelType type) { return 4 * Image::channelBytes(type); }

class GpuSpanRasterizer final : public EpiRasterizer {
 public:
  GpuSpanRasterizer(PixelType type, const EpiShading& shading) : type_(type) {
    if (shading.sliceHighlights)
      fail("--pst spans", "GPU spans do not add split highlight tracks; use exact");
    if (!shading.sliceVectors && shading.plan.passes().size() != 1)
      fail("--pst spans", "GPU spans shade diffuse scenes only (this one needs " + shading.plan.passNames() +
                              "); use exact");
    recordStride_ = GpuVertices::kRecordHead + shading.plan.extraCount;
    const GLint shared = gl::getInteger(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
    tile_ = int(std::min<GLint>(shared, 48 << 10) / 8);  // two uints per pixel
    std::string defines = "#define TILE " + std::to_string(tile_) + "\n";
    if (type == PixelType::F32) defines += "#define FLOAT_OUT\n";
    if (type == PixelType::Srgb8) defines += "#define SRGB\n";
    if (shading.sliceVectors) defines += std::string("#define VECTORS\n") + shading::glslTextureVector();
    const std::string library = PstGeometry::glslLibrary(recordStride_) + kTrack;
    tracks_ = gl::linkProgram("epi-span-tracks", {{GL_COMPUTE_SHADER, gl::glslHeader() + library + kTrackPass}});
    spansSource_ = defines + library + kSpans;
    program_ = linkSpans(false);
  }

  bool readsDeviceTable() const override { return true; }

  // The tile pass, writing to the storage buffer or (toLayers) a texture's layers.
  gl::Program linkSpans(bool toLayers) const {
    gl::Program p = gl::linkProgram(toLayers ? "epi-spans-to-layers" : "epi-spans",
                                    {{GL_COMPUTE_SHADER, gl::glslHeader() + (toLayers ? "#define IMAGE_OUT\n" : "") +
                                                             spansSource_}});
    if (type_ == PixelType::Srgb8) {
      const auto& upper = detail::srgb8Table().upper;
      gl::setUniform(p, "uSrgbUpper", std::span<const float>(upper.data(), 255));
    }
    return p;
  }

  void rasterize(const ExtremeVertices& v, const SliceTableView& slices, const ShearingCamera& cam, int row,
                 FrameSink& sink, RenderStats& stats) override {
    {
      ScopedStage s(stats.times, "upload");
      uploaded_ = GpuVertices::upload(v);
    }
    fill(*uploaded_, slices.device(), cam, row, sink, stats);
  }

  void rasterize(const GpuVertices& v, const GpuSliceTable& slices, const ShearingCamera& cam, int row,
                 FrameSink& sink, RenderStats& stats) override {
    fill(v, slices, cam, row, sink, stats);
  }

 private:
  // Columns x rows of one work group's tile: whole rows of the EPI when
  // four or more fit (the slices' walk is paid per row of a tile), else
  // four rows of a part of it.
  struct Tile {
    int columns, rows;
  };
  Tile tileFor(int width) const {
    const int columns = std::min(width, tile_ / 4);
    return {columns, tile_ / columns};
  }

  // The share's scanlines in batches of at most gBatchBytes of EPIs: one
  // batch is filled while the one before is copied out.
  void fill(const GpuVertices& v, const GpuSliceTable& table, const ShearingCamera& cam, int row, FrameSink& sink,
            RenderStats& stats) {
    if (v.recordStride != recordStride_) fail("GPU spans", "vertices carry another attribute count");
    const int n = cam.views(), w = cam.width();
    const size_t epiBytes = size_t(w) * n * pixelBytes(type_);
    const IndexRange lines = cam.share().scanlines;
    const int batch = int(std::clamp<size_t>(gBatchBytes / epiBytes, 1, size_t(std::min(lines.size(), 65535))));
    const Tile tile = tileFor(w);
    stats.counters["epis_per_dispatch"] = batch;
    stats.counters["tile_columns"] = tile.columns;
    stats.counters["tile_rows"] = tile.rows;
    if (const GLuint layers = isByteType(type_) ? sink.epiTexture(row, w, n, type_) : 0) {
      fillLayers(v, table, layers, lines, batch, n, w, tile, stats);
      return;
    }
    ReadbackRing ring(size_t(batch) * epiBytes);
    ImagePool pool;
    bind(program_, v, table, size_t(batch) * epiBytes, n, w, tile);
    int k = 0;
    for (int first = lines.begin; first < lines.end; first += batch, ++k) {
      const int count = std::min(batch, lines.end - first);
      const gl::Buffer& out = outputs_[size_t(k) % outputs_.size()];
      {
        ScopedStage s(stats.times, "raster");
        gl::GpuClock::mark("raster");
        out.bindStorage(kEpis);
        dispatch(program_, table, first, count, n, w, tile);
      }
      const EpiBatch epis(sink, pool, row, {first, first + count}, w, n, type_);
      {
        ScopedStage s(stats.times, "readback");
        gl::GpuClock::mark("readback");
        ring.readBuffer(out.id(), size_t(count) * epiBytes, epis.rows(0));
      }
      ring.submit([=, &sink] { epis.handOn(sink); });
    }
    ring.drain();
    stats.times.add("gpu_wait", ring.waitSeconds());
    gl::checkError("GPU spans");
  }

  // The sink's texture filled in place: the same dispatches, their tiles
  // stored into its layers; nothing waits for the GPU.
  void fillLayers(const GpuVertices& v, const GpuSliceTable& table, GLuint layers, IndexRange lines, int batch,
                  int n, int w, const Tile& tile, RenderStats& stats) {
    if (!layerProgram_) layerProgram_ = linkSpans(true);
    bind(layerProgram_, v, table, 0, n, w, tile);
    gl::BindImageTexture(kLayerUnit, layers, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32UI);
    {
      ScopedStage s(stats.times, "raster");
      gl::GpuClock::mark("raster");
      for (int first = lines.begin; first < lines.end; first += batch)
        dispatch(layerProgram_, table, first, std::min(batch, lines.end - first), n, w, tile);
    }
    gl::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gl::BindImageTexture(kLayerUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    gl::checkError("GPU spans into the sink's texture");
    stats.notes["epis"] = "texture";
  }

  // Buffers sized for this set, and everything that is the same for each
  // of its batches bound.
  void bind(const gl::Program& spans, const GpuVertices& v, const GpuSliceTable& table, size_t batchBytes, int n,
            int w, const Tile& tile) {
    for (gl::Buffer& b : outputs_)
      if (outputBytes_ < batchBytes) b = gl::makeBuffer<std::byte>(nullptr, batchBytes);
    outputBytes_ = std::max(outputBytes_, batchBytes);
    if (table.sliceCount() > trackCapacity_) {
      trackCapacity_ = table.sliceCount() + table.sliceCount() / 4;
      trackBuffer_ = gl::makeBuffer<std::byte>(nullptr, trackCapacity_ * kTrackBytes);
    }
    trackBuffer_.bindStorage(kTracks);
    if (v.hasVectors()) bindVectors(v);
    gl::setUniform(tracks_, "uViews", float(n));
    gl::setUniform(spans, "uViews", float(n));
    gl::setUniform(spans, "uWidth", w);
    gl::setUniform(spans, "uTileColumns", tile.columns);
    gl::setUniform(spans, "uTileRows", tile.rows);
    v.records.bindStorage(PstGeometry::kRecords);
    v.triangles.bindStorage(PstGeometry::kTriangles);
    table.bind(PstGeometry::kSlices, PstGeometry::kOffsets);
  }

  // Scanlines [first, first + count): their slices' tracks, then their
  // EPIs' tiles, by `spans` (into the bound output).
  void dispatch(const gl::Program& spans, const GpuSliceTable& table, int first, int count, int n, int w,
                const Tile& tile) {
    const uint32_t firstSlice = table.offsets()[size_t(first)];
    const uint32_t slices = table.offsets()[size_t(first + count)] - firstSlice;
    if (slices > 0) {
      tracks_.use();
      gl::setUniform(tracks_, "uFirst", GLuint(firstSlice));
      gl::setUniform(tracks_, "uCount", GLuint(slices));
      gl::dispatch((slices + 63) / 64, 1, 1);
    }
    spans.use();
    gl::setUniform(spans, "uFirstScanline", first);
    gl::DispatchCompute(GLuint((w + tile.columns - 1) / tile.columns), GLuint((n + tile.rows - 1) / tile.rows),
                        GLuint(count));
  }

  // Image slices' vectors and their texels (a buffer texture, as the GL
  // passes sample them).
  void bindVectors(const GpuVertices& v) {
    const GLint limit = gl::getInteger(GL_MAX_TEXTURE_BUFFER_SIZE);
    if (v.texelCount > size_t(limit))
      fail("GPU spans", "the row's " + std::to_string(v.texelCount) + " vector texels pass the GL's texture-buffer limit of " +
                            std::to_string(limit));
    texels_ = gl::Texture::overBuffer(GL_RGBA32F, v.texelBuffer);
    texels_.bind(kTexelUnit);
    v.vectors.bindStorage(kVectors);
  }

  static constexpr GLuint kEpis = 6, kTracks = 7, kVectors = 8, kTexelUnit = 3, kLayerUnit = 0;
  static constexpr size_t kTrackBytes = 48;  // kTrack's struct, std430
  PixelType type_;
  int recordStride_ = GpuVertices::kRecordHead;
  int tile_ = 0;  // pixels per work group's tile
  std::string spansSource_;  // the tile pass's GLSL, after the header
  gl::Program tracks_, program_, layerProgram_;  // the tile pass into buffers, and into layers (made when asked)
  gl::Buffer trackBuffer_;
  gl::Texture texels_;  // over the vertices' texel buffer
  size_t trackCapacity_ = 0;
  std::array<gl::Buffer, 2> outputs_;  // the batch being filled while the other is copied out
  size_t outputBytes_ = 0;
  std::optional<GpuVertices> uploaded_;  // host vertices, uploaded
};

}  // namespace

void setGpuSpanBatchBytes(size_t bytes) { gBatchBytes = bytes; }

std::unique_ptr<EpiRasterizer> makeGpuSpanRasterizer(PixelType type, const EpiShading& shading) {
  return std::make_unique<GpuSpanRasterizer>(type, shading);
}

}  // namespace mvr
