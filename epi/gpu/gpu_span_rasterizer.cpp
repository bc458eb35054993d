// The CPU span rasterizer's rule (epi/span_rasterizer.cpp) in compute
// shaders: no GL rasterization. On GPUs built for compute the graphics
// pipeline is a small part of the chip (an H100 runs vertex and fragment
// shaders on 2 of its 66 TPCs), and PSTs, a pixel or two wide and a whole
// track tall, are the worst shape for it: 287K PSTs into 640x1000 EPIs
// took the H100's rasterizer 139 ms of GPU time.
//
// A work group owns a tile of one EPI (columns x view rows) in on-chip
// memory and walks the scanline's slices, a thread per slice, a span per
// row, three times: the nearest depth of every pixel (atomic max of the
// float's bits: depth is reversed, in (0, 1]); then the first slice in
// table order that reaches it (atomic min of the slice's index), which is
// the CPU's "strictly nearer replaces" rule; then the winner's colour,
// shaded once per pixel. Tiles are written to a storage buffer in the
// stacked-EPI layout and copied into the readback ring.
#include <algorithm>
#include <array>
#include <optional>

#include "epi/epi_rasterizer.h"
#include "epi/gpu/pst_geometry.h"
#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/gpu_clock.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/image_pool.h"

namespace mvr {
namespace {

// Needs the slice library (PstGeometry::glslLibrary: End, sliceEnds, xAt).
// Arithmetic is the CPU's, term for term, and `precise` where a fused
// multiply-add would round otherwise; the GPU's division is within a few
// ulps of the CPU's, so a pixel may differ by a step where a span's end or
// a depth tie lands within that of a pixel centre.
const char* const kSpans = R"(
layout(local_size_x = 256) in;
layout(std430, binding = 5) readonly buffer Offsets { uint uOffsets[]; };
#ifdef FLOAT_OUT
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

int gViews, gX0, gXEnd, gI0, gIEnd;
uint gFirst;  // the scanline's first slice

// The pieces of epi/pst.cpp as rows of views [x, y) (centres in
// [rTop, rBottom)) and their facing.
struct Pieces { ivec2 rows[2]; bool front[2]; int count; };
void addPiece(inout Pieces p, float top, float bottom, bool front, bool cull) {
  if (!(bottom > top) || (!front && cull)) return;
  p.rows[p.count] = ivec2(max(0, int(ceil(top - 0.5))), min(gViews, int(ceil(bottom - 0.5))));
  p.front[p.count] = front;
  p.count += 1;
}
Pieces piecesOf(End e0, End e1, bool cull) {
  Pieces p;
  p.count = 0;
  float n = float(gViews);
  precise float dL = widthAt(e0, e1, 0.0), dR = widthAt(e0, e1, n);
  if ((dL < 0.0 && dR > 0.0) || (dL > 0.0 && dR < 0.0)) {
    precise float rStar = n * dL / (dL - dR);
    addPiece(p, 0.0, rStar, dL > 0.0, cull);
    addPiece(p, rStar, n, dR > 0.0, cull);
  } else if (dL != 0.0 || dR != 0.0) {
    addPiece(p, 0.0, n, dL + dR > 0.0, cull);
  }
  return p;
}

// A row's span: the row's left end xa and width, and the tile's columns
// [x, y) whose centres it covers.
struct Span { float xa, width; ivec2 columns; };
Span spanAt(End e0, End e1, int i) {
  Span s;
  float r = float(i) + 0.5;
  precise float xa = xAt(e0, r), x1 = xAt(e1, r);
  precise float width = x1 - xa, xb = xa + width;
  s.xa = xa;
  s.width = width;
  float lo = min(xa, xb), hi = max(xa, xb);
  // Clamped as floats: ends far outside the image stay representable.
  s.columns = ivec2(clamp(ceil(lo - 0.5), float(gX0), float(gXEnd)),
                    clamp(ceil(hi - 0.5), float(gX0), float(gXEnd)));
  if (!(width != 0.0)) s.columns = ivec2(0);  // no width, or NaN
  return s;
}
float uAt(Span s, int x) { precise float u = (float(x) + 0.5 - s.xa) / s.width; return clamp(u, 0.0, 1.0); }
float depthAt(End e0, End e1, float u) { precise float z = e0.depth + (e1.depth - e0.depth) * u; return z; }

// Phase 0: nearest depth per pixel; phase 1: first slice at that depth.
void visit(uint s, int phase) {
  End e0, e1;
  uint word;
  sliceEnds(s, e0, e1, word);
  Pieces p = piecesOf(e0, e1, (word >> 31) != 0u);
  for (int k = 0; k < p.count; ++k) {
    for (int i = max(p.rows[k].x, gI0); i < min(p.rows[k].y, gIEnd); ++i) {
      Span span = spanAt(e0, e1, i);
      uint row = uint((i - gI0) * uTileColumns - gX0);
      for (int x = span.columns.x; x < span.columns.y; ++x) {
        float z = depthAt(e0, e1, uAt(span, x));
        if (!(z > 0.0)) continue;  // behind the cleared depth, or NaN
        uint at = row + uint(x), bits = floatBitsToUint(z);
        if (phase == 0) atomicMax(sDepth[at], bits);
        else if (sDepth[at] == bits) atomicMin(sWinner[at], s - gFirst);
      }
    }
  }
}

vec4 shade(uint s, int i, int x) {
  End e0, e1;
  uint word;
  sliceEnds(s, e0, e1, word);
  Pieces p = piecesOf(e0, e1, (word >> 31) != 0u);
  bool front = p.front[p.count > 1 && i >= p.rows[1].x ? 1 : 0];
  float u = uAt(spanAt(e0, e1, i), x);
  int at = front ? 4 : 7;  // GpuVertices records: colour / w, front then back
  vec3 c0 = vec3(endAttribute(e0, at), endAttribute(e0, at + 1), endAttribute(e0, at + 2));
  vec3 c1 = vec3(endAttribute(e1, at), endAttribute(e1, at + 1), endAttribute(e1, at + 2));
  precise float invW = e0.invW + (e1.invW - e0.invW) * u;
  precise vec3 c = (c0 + (c1 - c0) * u) / invW;
  return vec4(clamp(c, 0.0, 1.0), 1.0);
}

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
  gViews = int(uViews);
  gX0 = int(gl_WorkGroupID.x) * uTileColumns;
  gXEnd = min(uWidth, gX0 + uTileColumns);
  gI0 = int(gl_WorkGroupID.y) * uTileRows;
  gIEnd = min(gViews, gI0 + uTileRows);
  uint j = uint(uFirstScanline) + gl_WorkGroupID.z, tid = gl_LocalInvocationIndex;
  uint pixels = uint(uTileColumns * uTileRows);
  for (uint at = tid; at < pixels; at += 256u) { sDepth[at] = 0u; sWinner[at] = 0xFFFFFFFFu; }
  gFirst = uOffsets[j];
  uint last = uOffsets[j + 1u];
  barrier();
  for (uint s = gFirst + tid; s < last; s += 256u) visit(s, 0);
  barrier();
  for (uint s = gFirst + tid; s < last; s += 256u) visit(s, 1);
  barrier();
  for (uint at = tid; at < pixels; at += 256u) {
    int x = gX0 + int(at) % uTileColumns, i = gI0 + int(at) / uTileColumns;
    if (x >= gXEnd || i >= gIEnd) continue;
    uint winner = sWinner[at];
    vec4 c = winner == 0xFFFFFFFFu ? vec4(0.0) : shade(gFirst + winner, i, x);
    uint dst = (gl_WorkGroupID.z * uint(gViews) + uint(i)) * uint(uWidth) + uint(x);
#ifdef FLOAT_OUT
    uEpis[dst] = c;
#else
    uEpis[dst] = winner == 0xFFFFFFFFu ? 0u
                 : byteOf(c.r) | byteOf(c.g) << 8 | byteOf(c.b) << 16 | 255u << 24;
#endif
  }
}
)";

// Storage for one batch's EPIs: each slot's bytes at most (the copy into
// the readback ring is as large).
constexpr size_t kBatchBudget = size_t(64) << 20;

size_t pixelBytes(PixelType type) { return 4 * Image::channelBytes(type); }

class GpuSpanRasterizer final : public EpiRasterizer {
 public:
  GpuSpanRasterizer(PixelType type, const EpiShading& shading) : type_(type) {
    if (shading.sliceVectors || shading.plan.passes().size() != 1)
      fail("--pst spans", "GPU spans shade diffuse scenes only (this one needs " + shading.plan.passNames() +
                              "); use exact");
    recordStride_ = GpuVertices::kRecordHead + shading.plan.extraCount;
    GLint shared = 0;
    gl::GetIntegerv(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE, &shared);
    tile_ = int(std::min<GLint>(shared, 48 << 10) / 8);  // two uints per pixel
    std::string defines = "#define TILE " + std::to_string(tile_) + "\n";
    if (type == PixelType::F32) defines += "#define FLOAT_OUT\n";
    if (type == PixelType::Srgb8) defines += "#define SRGB\n";
    program_ = gl::linkProgram("epi-spans", {{GL_COMPUTE_SHADER, gl::glslHeader() + defines +
                                                                    PstGeometry::glslLibrary(recordStride_) + kSpans}});
    if (type == PixelType::Srgb8) {
      const auto& upper = detail::srgb8Table().upper;
      gl::ProgramUniform1fv(program_.id(), gl::GetUniformLocation(program_.id(), "uSrgbUpper"), 255, upper.data());
    }
  }

  bool readsDeviceTable() const override { return true; }

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
  void fill(const GpuVertices& v, const GpuSliceTable& table, const ShearingCamera& cam, int row, FrameSink& sink,
            RenderStats& stats) {
    if (v.recordStride != recordStride_) fail("GPU spans", "vertices carry another attribute count");
    const int n = cam.views(), w = cam.width();
    const size_t epiBytes = size_t(w) * n * pixelBytes(type_);
    const IndexRange lines = cam.share().scanlines;
    const int batch = int(std::clamp<size_t>(kBatchBudget / epiBytes, 1, size_t(std::min(lines.size(), 65535))));
    const Tile tile = tileFor(w);
    ReadbackRing ring(size_t(batch) * epiBytes);
    for (gl::Buffer& b : outputs_)
      if (outputBytes_ < size_t(batch) * epiBytes) b = gl::makeBuffer<std::byte>(nullptr, size_t(batch) * epiBytes);
    outputBytes_ = std::max(outputBytes_, size_t(batch) * epiBytes);
    ImagePool pool;
    gl::UseProgram(program_.id());
    gl::setUniform(program_, "uViews", float(n));
    gl::setUniform(program_, "uWidth", w);
    gl::setUniform(program_, "uTileColumns", tile.columns);
    gl::setUniform(program_, "uTileRows", tile.rows);
    gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, PstGeometry::kRecords, v.records.id());
    gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, PstGeometry::kTriangles, v.triangles.id());
    table.bind(PstGeometry::kSlices, PstGeometry::kOffsets);
    int k = 0;
    for (int first = lines.begin; first < lines.end; first += batch, ++k) {
      const int count = std::min(batch, lines.end - first);
      const gl::Buffer& out = outputs_[size_t(k) % outputs_.size()];
      {
        ScopedStage s(stats.times, "raster");
        gl::GpuClock::mark("raster");
        gl::setUniform(program_, "uFirstScanline", first);
        gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, kEpis, out.id());
        gl::DispatchCompute(GLuint((w + tile.columns - 1) / tile.columns), GLuint((n + tile.rows - 1) / tile.rows),
                            GLuint(count));
      }
      const std::vector<std::shared_ptr<Image>> epis = pool.take(count, w, n, type_);
      {
        ScopedStage s(stats.times, "readback");
        gl::GpuClock::mark("readback");
        std::vector<std::byte*> dsts;
        for (const auto& epi : epis) dsts.push_back(reinterpret_cast<std::byte*>(epi->row(0)));
        ring.readBuffer(out.id(), size_t(count) * epiBytes, dsts);
      }
      ring.submit([=, &sink] {
        for (int e = 0; e < count; ++e) sink.putEpiInPlace(row, first + e, *epis[size_t(e)]);
      });
    }
    ring.drain();
    stats.times.add("gpu_wait", ring.waitSeconds());
    gl::checkError("GPU spans");
    stats.counters["epis_per_dispatch"] = batch;
    stats.counters["tile_columns"] = tile.columns;
    stats.counters["tile_rows"] = tile.rows;
  }

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

  static constexpr GLuint kEpis = 6;
  PixelType type_;
  int recordStride_ = GpuVertices::kRecordHead;
  int tile_ = 0;  // pixels per work group's tile
  gl::Program program_;
  std::array<gl::Buffer, 2> outputs_;  // the batch being filled while the other is copied out
  size_t outputBytes_ = 0;
  std::optional<GpuVertices> uploaded_;  // host vertices, uploaded
};

}  // namespace

std::unique_ptr<EpiRasterizer> makeGpuSpanRasterizer(PixelType type, const EpiShading& shading) {
  return std::make_unique<GpuSpanRasterizer>(type, shading);
}

}  // namespace mvr
