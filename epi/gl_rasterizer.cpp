// GL rasterization of PSTs. EPIs of many scanlines are stacked in one tall
// framebuffer (EPI b occupies rows [b N, (b + 1) N)), so one draw call
// fills a whole batch. PST geometry is a triangle strip per piece, joined by
// primitive restart:
//   quad   one sliver: two triangles, attributes interpolated linearly.
//   strip  K slivers between rulings (tracks of fixed 3D points) where the
//          attributes are exact; K grows with the twist |dTop - dBottom| and
//          the perspective ratio, capped by the wider p-edge's pixel width.
//   exact  one sliver; the fragment shader solves u = (x - x0(r)) / d(r)
//          from two linearly interpolated quantities (both are affine in x
//          and r) and interpolates colour hyperbolically and depth exactly.
#include <algorithm>
#include <cmath>

#include "epi/epi_rasterizer.h"
#include "epi/pst.h"
#include "mvr/error.h"
#include "mvr/gl_program.h"
#include "mvr/progress.h"
#include "mvr/render_target.h"

namespace mvr {
namespace {

const char* const kSimpleVertex = R"(
layout(location = 0) in vec2 aPos;     // EPI pixels: x, stacked row
layout(location = 1) in float aDepth;
layout(location = 2) in vec3 aColor;
uniform vec2 uScale;
noperspective out vec3 vColor;
void main() {
  gl_Position = vec4(aPos * uScale - 1.0, aDepth, 1.0);
  vColor = aColor;
}
)";

const char* const kSimpleFragment = R"(
noperspective in vec3 vColor;
layout(location = 0) out vec4 oColor;
void main() { oColor = vec4(vColor, 1.0); }
)";

const char* const kExactVertex = R"(
layout(location = 0) in vec2 aPos;
layout(location = 1) in vec2 aNumDen;   // x - x0(r), x1(r) - x0(r)
layout(location = 2) in vec4 aEnds;     // depth0, depth1, 1/w0, 1/w1
layout(location = 3) in vec3 aColor0;   // colour / w at the ends
layout(location = 4) in vec3 aColor1;
uniform vec2 uScale;
noperspective out vec2 vNumDen;
flat out vec4 vEnds;
flat out vec3 vColor0;
flat out vec3 vColor1;
void main() {
  gl_Position = vec4(aPos * uScale - 1.0, aEnds.x, 1.0);
  vNumDen = aNumDen;
  vEnds = aEnds;
  vColor0 = aColor0;
  vColor1 = aColor1;
}
)";

const char* const kExactFragment = R"(
noperspective in vec2 vNumDen;
flat in vec4 vEnds;
flat in vec3 vColor0;
flat in vec3 vColor1;
layout(location = 0) out vec4 oColor;
void main() {
  float u = vNumDen.y == 0.0 ? 0.0 : clamp(vNumDen.x / vNumDen.y, 0.0, 1.0);
  float invW = mix(vEnds.z, vEnds.w, u);
  oColor = vec4(mix(vColor0, vColor1, u) / invW, 1.0);
  gl_FragDepth = mix(vEnds.x, vEnds.y, u);
}
)";

struct SimpleVertex {
  float x, y, depth;
  glm::vec3 color;
};

struct ExactVertex {
  float x, y, num, den;
  glm::vec4 ends;
  glm::vec3 c0, c1;
};

constexpr uint32_t kRestart = 0xFFFFFFFFu;

// Slivers for strip mode. The attribute of a pixel inside a sliver between
// rulings u_a, u_b is misplaced by at most (u_b - u_a) |dTop - dBottom| / 4
// pixels (affine interpolation over the sliver's triangles); half a pixel
// is the target. Perspective adds |1 - w_near / w_far| of the slice width.
int sliverCount(const Pst& pst, const PstPiece& piece) {
  const float dTop = pst.width(piece.rTop), dBottom = pst.width(piece.rBottom);
  const float widest = std::max(std::abs(dTop), std::abs(dBottom));
  const float iw0 = pst.e0.invW, iw1 = pst.e1.invW;
  const float perspective = 1.0f - std::min(iw0, iw1) / std::max(iw0, iw1);
  const float need = std::max(std::abs(dTop - dBottom) / 2.0f, widest * perspective / 2.0f);
  return std::clamp(int(std::ceil(need)), 1, std::max(1, int(std::ceil(widest))));
}

class GlRasterizer final : public EpiRasterizer {
 public:
  GlRasterizer(PstMode mode, PixelType type) : mode_(mode), type_(type) {
    if (mode == PstMode::Exact)
      program_ = gl::linkProgram("epi-exact", {{GL_VERTEX_SHADER, gl::glslHeader() + kExactVertex},
                                               {GL_FRAGMENT_SHADER, gl::glslHeader() + kExactFragment}});
    else
      program_ = gl::linkProgram("epi", {{GL_VERTEX_SHADER, gl::glslHeader() + kSimpleVertex},
                                         {GL_FRAGMENT_SHADER, gl::glslHeader() + kSimpleFragment}});
    vao_ = gl::VertexArray::create();
  }

  void rasterize(const ExtremeVertices& v, const SliceTable& table, const ShearingCamera& cam,
                 int row, FrameSink& sink, RenderStats& stats) override {
    GLint maxSize = 4096;
    gl::GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = cam.views(), w = cam.width(), h = cam.height();
    const int chunkRows = std::min(n, int(maxSize));  // views per tile
    const int chunks = (n + chunkRows - 1) / chunkRows;
    const size_t bytesPerRow = size_t(w) * (4 * Image::channelBytes(type_) + 4);
    const int budgetRows = int(std::max<size_t>(chunkRows, (size_t(256) << 20) / bytesPerRow));
    const int batch = chunks > 1 ? 1 : std::clamp(std::min(int(maxSize), budgetRows) / n, 1, h);
    RenderTarget target(w, batch * chunkRows, type_);
    setDepthConvention();
    target.bind();
    gl::UseProgram(program_.id());
    gl::setUniform(program_, "uScale", glm::vec2(2.0f / w, 2.0f / (batch * chunkRows)));
    gl::Enable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    Progress progress("mvr " + std::string(pstModeName(mode_)), h);
    std::vector<Image> epis(batch);
    for (int first = 0; first < h; first += batch) {
      const int count = std::min(batch, h - first);
      for (int k = 0; k < count; ++k) epis[k] = Image(w, n, type_);
      for (int c = 0; c < chunks; ++c) {
        const int view0 = c * chunkRows, views = std::min(chunkRows, n - view0);
        {
          ScopedStage s(stats.times, "pst");
          clearGeometry();
          for (int k = 0; k < count; ++k)
            emitScanline(v, table, first + k, n, float(k * chunkRows - view0));
        }
        {
          ScopedStage s(stats.times, "raster");
          target.clear();
          drawGeometry();
          gl::Finish();
        }
        ScopedStage s(stats.times, "readback");
        for (int k = 0; k < count; ++k) target.readRows(k * chunkRows, views, epis[k], view0);
      }
      for (int k = 0; k < count; ++k) {
        sink.putEpi(row, first + k, epis[k]);
        progress.step();
      }
    }
    gl::Disable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    gl::checkError("EPI rasterization");
    stats.counters["epis_per_draw"] = batch;
    stats.counters["pst_vertices"] += double(verticesEmitted_);
    verticesEmitted_ = 0;
  }

 private:
  void clearGeometry() {
    simple_.clear();
    exact_.clear();
    indices_.clear();
  }

  // yBase: framebuffer row of EPI row coordinate r = 0 for this scanline.
  void emitScanline(const ExtremeVertices& v, const SliceTable& table, int j, int n, float yBase) {
    for (const Slice& s : table.scanline(j)) {
      auto [e0, e1] = sliceEnds(v, s);
      const Pst pst = makePst(e0, e1, n, v.cullBack[s.triangle]);
      for (int p = 0; p < pst.pieceCount; ++p) emitPiece(pst, pst.pieces[p], yBase);
    }
  }

  void emitPiece(const Pst& pst, const PstPiece& piece, float yBase) {
    const int slivers = mode_ == PstMode::Strip ? sliverCount(pst, piece) : 1;
    const float rows[2] = {piece.rTop, piece.rBottom};
    const float iw0 = pst.e0.invW, iw1 = pst.e1.invW;
    for (int k = 0; k <= slivers; ++k) {
      // Rulings evenly spaced in the 3D parameter s, where attributes are
      // linear; the screen parameter is u = s iw0 / ((1 - s) iw1 + s iw0).
      const float s = float(k) / slivers;
      const float u = k == slivers ? 1.0f : s * iw0 / ((1.0f - s) * iw1 + s * iw0);
      for (float r : rows) {
        const float x = pst.x0(r) + u * pst.width(r);
        indices_.push_back(uint32_t(mode_ == PstMode::Exact ? exact_.size() : simple_.size()));
        if (mode_ == PstMode::Exact) {
          const glm::vec3 c0 = piece.front ? pst.e0.frontOverW : pst.e0.backOverW;
          const glm::vec3 c1 = piece.front ? pst.e1.frontOverW : pst.e1.backOverW;
          exact_.push_back({x, yBase + r, x - pst.x0(r), pst.width(r),
                            glm::vec4(pst.e0.depth, pst.e1.depth, iw0, iw1), c0, c1});
        } else {
          simple_.push_back({x, yBase + r, pstDepth(pst, u), pstColor(pst, piece.front, u)});
        }
      }
    }
    indices_.push_back(kRestart);
  }

  void drawGeometry() {
    if (indices_.empty()) return;
    verticesEmitted_ += mode_ == PstMode::Exact ? exact_.size() : simple_.size();
    gl::Buffer vertices = mode_ == PstMode::Exact ? gl::makeBuffer(exact_.data(), exact_.size())
                                                  : gl::makeBuffer(simple_.data(), simple_.size());
    gl::Buffer indices = gl::makeBuffer(indices_.data(), indices_.size());
    const GLuint vao = vao_.id();
    auto attrib = [&](GLuint loc, int comps, size_t offset) {
      gl::VertexArrayAttribFormat(vao, loc, comps, GL_FLOAT, GL_FALSE, GLuint(offset));
      gl::VertexArrayAttribBinding(vao, loc, 0);
      gl::EnableVertexArrayAttrib(vao, loc);
    };
    if (mode_ == PstMode::Exact) {
      gl::VertexArrayVertexBuffer(vao, 0, vertices.id(), 0, sizeof(ExactVertex));
      attrib(0, 2, offsetof(ExactVertex, x));
      attrib(1, 2, offsetof(ExactVertex, num));
      attrib(2, 4, offsetof(ExactVertex, ends));
      attrib(3, 3, offsetof(ExactVertex, c0));
      attrib(4, 3, offsetof(ExactVertex, c1));
    } else {
      gl::VertexArrayVertexBuffer(vao, 0, vertices.id(), 0, sizeof(SimpleVertex));
      attrib(0, 2, offsetof(SimpleVertex, x));
      attrib(1, 1, offsetof(SimpleVertex, depth));
      attrib(2, 3, offsetof(SimpleVertex, color));
    }
    gl::VertexArrayElementBuffer(vao, indices.id());
    gl::BindVertexArray(vao);
    gl::DrawElements(GL_TRIANGLE_STRIP, GLsizei(indices_.size()), GL_UNSIGNED_INT, nullptr);
  }

  PstMode mode_;
  PixelType type_;
  gl::Program program_;
  gl::VertexArray vao_;
  std::vector<SimpleVertex> simple_;
  std::vector<ExactVertex> exact_;
  std::vector<uint32_t> indices_;
  size_t verticesEmitted_ = 0;
};

}  // namespace

PstMode parsePstMode(const std::string& name) {
  if (name == "quad") return PstMode::Quad;
  if (name == "strip") return PstMode::Strip;
  if (name == "exact") return PstMode::Exact;
  if (name == "cpu") return PstMode::Cpu;
  fail("--pst", "unknown mode '" + name + "' (expected quad, strip, exact or cpu)");
}

const char* pstModeName(PstMode mode) {
  switch (mode) {
    case PstMode::Quad: return "quad";
    case PstMode::Strip: return "strip";
    case PstMode::Exact: return "exact";
    case PstMode::Cpu: return "cpu";
  }
  return "?";
}

std::unique_ptr<EpiRasterizer> makeGlRasterizer(PstMode mode, PixelType type) {
  if (mode == PstMode::Cpu) fail("--pst", "cpu is not a GL mode");
  return std::make_unique<GlRasterizer>(mode, type);
}

}  // namespace mvr
