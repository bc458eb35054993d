#include "epi/gpu/pst_geometry.h"

#include <algorithm>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"

namespace mvr {
namespace {

// What the count pass and the vertex shaders share: the slice table, the
// endpoint records, and sliceEnds() as in slicing/slice_table.cpp.
const char* const kLibrary = R"(
layout(std430, binding = 2) readonly buffer Records { float uRecords[]; };
layout(std430, binding = 3) readonly buffer Triangles { uvec4 uTriangles[]; };  // a, b, c, material | cull << 31
layout(std430, binding = 4) readonly buffer Slices { uvec4 uSlices[]; };  // triangle, tLong, tShort, flags
uniform uint uFirstSlice;  // the batch: slices [uFirstSlice, uFirstSlice + uSliceCount)
uniform uint uSliceCount;
uniform float uViews;

// A slice endpoint: a point on the edge from vertex p to vertex q.
struct End { uint p, q; float t, x0, dx, depth, invW; };

float recordAt(uint p, uint q, float t, int at) {
  float a = uRecords[p * uint(RECORD) + uint(at)], b = uRecords[q * uint(RECORD) + uint(at)];
  return a + (b - a) * t;
}
float endAttribute(End e, int at) { return recordAt(e.p, e.q, e.t, at); }
End endAt(uint p, uint q, float t) {
  End e;
  e.p = p; e.q = q; e.t = t;
  e.x0 = recordAt(p, q, t, 0);
  e.dx = recordAt(p, q, t, 1);
  e.depth = recordAt(p, q, t, 2);
  e.invW = recordAt(p, q, t, 3);
  return e;
}
void sliceEnds(uint s, out End e0, out End e1, out uint word) {
  uvec4 slice = uSlices[s];
  uvec4 tri = uTriangles[slice.x];
  word = tri.w;
  uint flags = slice.w;
  if ((flags & 256u) != 0u) {  // a segment
    e0 = endAt(tri.x, tri.x, 0.0);
    e1 = endAt(tri.y, tri.y, 0.0);
    return;
  }
  uint a = tri[flags & 3u], b = tri[(flags >> 2) & 3u], c = tri[(flags >> 4) & 3u];
  End onLong = endAt(a, c, uintBitsToFloat(slice.y));
  End onShort = (flags & 64u) != 0u ? endAt(b, c, uintBitsToFloat(slice.z))
                                    : endAt(a, b, uintBitsToFloat(slice.z));
  bool swapped = (flags & 128u) != 0u;
  e0 = swapped ? onShort : onLong;
  e1 = swapped ? onLong : onShort;
}
float xAt(End e, float r) { return e.x0 + (r - 0.5) * e.dx; }
float widthAt(End e0, End e1, float r) { return xAt(e1, r) - xAt(e0, r); }

// epi/pst.cpp's makePst over N = n views: piece 0 runs from row 0 to the
// edge-on view r* where the i-edges cross (Halle 5.6.3), else to N; piece
// 1 from r* to N when they cross. Each has its facing, and is drawn unless
// it is empty or faces away from a culled triangle. `precise`: the CPU's
// rounding, so that every pass finds the same r*.
struct PstPieces { vec2 top, bottom; bvec2 front, drawn; bool split; };
PstPieces pstPieces(End e0, End e1, float n, bool cull) {
  PstPieces p;
  precise float dL = widthAt(e0, e1, 0.0), dR = widthAt(e0, e1, n);
  p.split = (dL < 0.0 && dR > 0.0) || (dL > 0.0 && dR < 0.0);
  precise float rStar = p.split ? n * dL / (dL - dR) : n;
  p.top = vec2(0.0, rStar);
  p.bottom = vec2(rStar, n);
  p.front = p.split ? bvec2(dL > 0.0, dR > 0.0) : bvec2(dL + dR > 0.0, false);
  p.drawn = bvec2(p.bottom.x > p.top.x && (dL != 0.0 || dR != 0.0) && (p.front.x || !cull),
                  p.split && p.bottom.y > p.top.y && (p.front.y || !cull));
  return p;
}
)";

// Per slice: its pieces (epi/pst.cpp) and their sliver counts
// (sliverCount in gl_rasterizer.cpp), as vertex counts for the prefix sum
// and a packed record for the vertex shaders: (K0 | K1 << 16, batch
// scanline | flags << 16), flags: 1 split at r*, 2 piece 0 faces front,
// 4 piece 1 faces front. K = 0: the piece is absent or culled.
const char* const kCount = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 5) readonly buffer Offsets { uint uOffsets[]; };
layout(std430, binding = 6) writeonly buffer FirstVertex { uint uFirstVertex[]; };
layout(std430, binding = 7) writeonly buffer Pieces { uvec2 uPieces[]; };
uniform uint uFirstScanline;
uniform uint uScanlines;
uniform bool uStrip;

uint slivers(End e0, End e1, float top, float bottom) {
  if (!uStrip) return 1u;
  float dTop = widthAt(e0, e1, top), dBottom = widthAt(e0, e1, bottom);
  float widest = max(abs(dTop), abs(dBottom));
  float perspective = 1.0 - min(e0.invW, e1.invW) / max(e0.invW, e1.invW);
  float need = max(abs(dTop - dBottom) / 2.0, widest * perspective / 2.0);
  float cap = clamp(ceil(widest), 1.0, 65535.0);
  return uint(clamp(ceil(need), 1.0, cap));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uSliceCount) return;
  uint s = uFirstSlice + i;
  uint lo = uFirstScanline, hi = uFirstScanline + uScanlines - 1u;  // last j with offsets[j] <= s
  while (lo < hi) {
    uint mid = (lo + hi + 1u) >> 1;
    if (uOffsets[mid] <= s) lo = mid; else hi = mid - 1u;
  }
  End e0, e1;
  uint word;
  sliceEnds(s, e0, e1, word);
  PstPieces pieces = pstPieces(e0, e1, uViews, (word >> 31) != 0u);
  uint k0 = pieces.drawn.x ? slivers(e0, e1, pieces.top.x, pieces.bottom.x) : 0u;
  uint k1 = pieces.drawn.y ? slivers(e0, e1, pieces.top.y, pieces.bottom.y) : 0u;
  uint flags = (pieces.split ? 1u : 0u) | (pieces.front.x ? 2u : 0u) | (pieces.front.y ? 4u : 0u);
  uFirstVertex[i] = 6u * (k0 + k1);
  uPieces[i] = uvec2(k0 | (k1 << 16), (lo - uFirstScanline) | (flags << 16));
}
)";

// Vertex v of the batch: the slice whose first vertex is the last one at
// or before v; then piece, sliver and corner. Corners 0-5 are (ruling k,
// top), (k, bottom), (k + 1, top), (k + 1, top), (k, bottom), (k + 1,
// bottom): bit c of 0x2C says ruling k + 1, of 0x32 the bottom row.
const char* const kPull = R"(
layout(std430, binding = 6) readonly buffer FirstVertex { uint uFirstVertex[]; };
layout(std430, binding = 7) readonly buffer Pieces { uvec2 uPieces[]; };
uniform int uChunkRows;
uniform int uView0;

struct PstVertex {
  uint slice;  // in the batch
  End e0, e1;
  float x, y;  // framebuffer position (pixels)
  float r;     // EPI row coordinate
  float u;     // screen-space slice parameter
  bool front;
  float material;
  uint triangle;
};

PstVertex pullPstVertex() {
  uint v = uint(gl_VertexID), lo = 0u, hi = uSliceCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) >> 1;
    if (uFirstVertex[mid] <= v) lo = mid; else hi = mid - 1u;
  }
  uint local = v - uFirstVertex[lo];
  uvec2 piece = uPieces[lo];
  uint k0 = piece.x & 0xFFFFu, k1 = piece.x >> 16, flags = piece.y >> 16;
  PstVertex p;
  uint word;
  sliceEnds(uFirstSlice + lo, p.e0, p.e1, word);
  p.slice = lo;
  p.triangle = uSlices[uFirstSlice + lo].x;
  p.material = float(word & 0x7FFFFFFFu);
  bool second = local >= 6u * k0;
  if (second) local -= 6u * k0;
  PstPieces pieces = pstPieces(p.e0, p.e1, uViews, false);
  float top = second ? pieces.top.y : pieces.top.x, bottom = second ? pieces.bottom.y : pieces.bottom.x;
  p.front = (flags & (second ? 4u : 2u)) != 0u;
  uint slivers = second ? k1 : k0, corner = local % 6u;
  uint ruling = local / 6u + ((0x2Cu >> corner) & 1u);
  p.r = ((0x32u >> corner) & 1u) != 0u ? bottom : top;
  // Rulings evenly spaced in the 3D parameter, as the CPU's strips.
  float s = float(ruling) / float(slivers), iw0 = p.e0.invW, iw1 = p.e1.invW;
  p.u = ruling == slivers ? 1.0 : s * iw0 / ((1.0 - s) * iw1 + s * iw0);
  p.x = xAt(p.e0, p.r) + p.u * widthAt(p.e0, p.e1, p.r);
  p.y = float(int(piece.y & 0xFFFFu) * uChunkRows - uView0) + p.r;
  return p;
}
)";

// A slice's own vector (image slices: one per "triangle").
const char* const kTriangleVectors = R"(
layout(std430, binding = 8) readonly buffer Vectors { uvec4 uVectors[]; };  // GpuVertices::vectors
uvec4 sliceVector(PstVertex p) { return uVectors[p.triangle]; }
)";

// Vectors extracted per slice of the batch (SceneVectors).
const char* const kBatchVectors = R"(
uvec4 sliceVector(PstVertex p) { return sliceVector(p.slice); }
)";

std::string recordDefine(int stride) { return "#define RECORD " + std::to_string(stride) + "\n"; }

struct DrawArraysIndirectCommand {
  uint32_t count, instanceCount, first, baseInstance;
};

}  // namespace

std::string PstGeometry::glslLibrary(int recordStride) { return recordDefine(recordStride) + kLibrary; }

std::string PstGeometry::glslPull(int recordStride, bool sceneVectors) {
  return glslLibrary(recordStride) + kPull +
         (sceneVectors ? std::string(SceneVectors::glslPull()) + kBatchVectors : kTriangleVectors);
}

PstGeometry::PstGeometry(PstMode mode, int extraCount, const SceneTexturing* texturing)
    : mode_(mode), recordStride_(GpuVertices::kRecordHead + extraCount) {
  if (mode == PstMode::Cpu) fail("PstGeometry", "cpu is not a GL mode");
  if (texturing) {
    sceneVectors_.emplace(glslLibrary(recordStride_), GpuVertices::kRecordHead + texturing->uv, texturing->textures);
    materials_ = &texturing->materials;
  }
  count_ = gl::linkProgram("pst-count", {{GL_COMPUTE_SHADER, gl::glslHeader() + recordDefine(recordStride_) +
                                                                 kLibrary + kCount}});
  const DrawArraysIndirectCommand command{0, 1, 0, 0};
  indirect_ = gl::makeBuffer(&command, 1, GL_DYNAMIC_STORAGE_BIT);
  vao_ = gl::VertexArray::create();
}

void PstGeometry::build(const GpuVertices& vertices, const GpuSliceTable& table, int first, int count,
                        int views) {
  if (vertices.recordStride != recordStride_) fail("PstGeometry", "vertices carry another attribute count");
  const auto& offsets = table.offsets();
  if (vertices.hasVectors()) viewTexels(vertices);
  vertices_ = &vertices;
  table_ = &table;
  firstSlice_ = offsets[first];
  sliceCount_ = offsets[first + count] - offsets[first];
  views_ = views;
  if (sliceCount_ > capacity_) {
    capacity_ = sliceCount_ + sliceCount_ / 4;
    firstVertex_ = gl::makeBuffer<uint32_t>(nullptr, capacity_);
    pieces_ = gl::makeBuffer<glm::uvec2>(nullptr, capacity_);
  }
  if (sliceCount_ > 0) {
    count_.use();
    setSliceUniforms(count_);
    gl::setUniform(count_, "uFirstScanline", GLuint(first));
    gl::setUniform(count_, "uScanlines", GLuint(count));
    gl::setUniform(count_, "uStrip", mode_ == PstMode::Strip ? 1 : 0);
    bindBuffers();
    gl::bindStorage(kOffsets, table.offsetsBuffer());
    gl::dispatch((sliceCount_ + 63) / 64, 1, 1);
  }
  prefixSum_.exclusive(firstVertex_.id(), 0, sliceCount_, indirect_.id(), 0);
  if (sceneVectors_) {
    bindBuffers();
    sceneVectors_->build(firstSlice_, sliceCount_, views_, *materials_);
  }
}

size_t PstGeometry::vectorTexels() const { return sceneVectors_ ? sceneVectors_->texelCount() : 0; }

void PstGeometry::setSliceUniforms(const gl::Program& p) const {
  gl::setUniform(p, "uFirstSlice", GLuint(firstSlice_));
  gl::setUniform(p, "uSliceCount", GLuint(sliceCount_));
  gl::setUniform(p, "uViews", float(views_));
}

void PstGeometry::bindBuffers() const {
  vertices_->records.bindStorage(kRecords);
  vertices_->triangles.bindStorage(kTriangles);
  gl::bindStorage(kSlices, table_->slicesBuffer());
  firstVertex_.bindStorage(kFirstVertex);
  pieces_.bindStorage(kPieces);
}

void PstGeometry::bind(const gl::Program& program, int chunkRows, int view0) const {
  setSliceUniforms(program);
  gl::setUniform(program, "uChunkRows", chunkRows);
  gl::setUniform(program, "uView0", view0);
  bindBuffers();
  if (sceneVectors_) sceneVectors_->bind(kVectorUnit);
  else if (vertices_->hasVectors()) bindVectors();
}

void PstGeometry::bindVectors() const {
  vertices_->vectors.bindStorage(kVectors);
  texels_.bind(kVectorUnit);
}

void PstGeometry::viewTexels(const GpuVertices& v) {
  const GLint limit = gl::getInteger(GL_MAX_TEXTURE_BUFFER_SIZE);
  if (v.texelCount > size_t(limit))
    fail("PstGeometry", "the row's " + std::to_string(v.texelCount) +
                            " vector texels pass the GL's texture-buffer limit of " + std::to_string(limit));
  texels_ = gl::Texture::overBuffer(GL_RGBA32F, v.texelBuffer);
}

void PstGeometry::draw() const {
  if (sliceCount_ == 0) return;
  vao_.bind();
  gl::BindBuffer(GL_DRAW_INDIRECT_BUFFER, indirect_.id());
  gl::DrawArraysIndirect(GL_TRIANGLES, nullptr);
  gl::BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

}  // namespace mvr
