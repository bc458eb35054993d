// GL rasterization of PSTs. EPIs of many scanlines are stacked in one tall
// framebuffer (EPI b occupies rows [b N, (b + 1) N)), so one draw call per
// shading pass fills a whole batch. PST geometry is a triangle strip per
// piece, joined by primitive restart:
//   quad   one sliver: two triangles, attributes interpolated linearly.
//   strip  K slivers between rulings (tracks of fixed 3D points) where the
//          attributes are exact; K grows with the twist |dTop - dBottom| and
//          the perspective ratio, capped by the wider p-edge's pixel width.
//   exact  one sliver; the fragment shader solves u = (x - x0(r)) / d(r)
//          from two linearly interpolated quantities (both are affine in x
//          and r) and interpolates attributes hyperbolically and depth
//          exactly.
// Scenes that need more than the diffuse pass accumulate the passes
// (epi/epi_pass.h) in a float target.
//
// Where the geometry is built: on the GPU (epi/gpu/pst_geometry.h: the
// slice table stays in GPU memory, a compute pass and a prefix sum per
// batch, vertices pulled by the passes' vertex shaders), or on the CPU
// (below: vertices emitted per batch and uploaded). Split highlight
// tracks (interp's --splits) take the CPU path.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>

#include "epi/epi_batch.h"
#include "epi/epi_rasterizer.h"
#include "epi/gpu/epi_pass.h"
#include "epi/gpu/pst_geometry.h"
#include "epi/pst.h"
#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/gl/gpu_clock.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/image_pool.h"
#include "mvr/gl/render_target.h"
#include "shading/gpu_materials.h"
#include "shading/texture_vector.h"

namespace mvr {
namespace {

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
  GlRasterizer(PstMode mode, PixelType type, const EpiShading& shading, PstBuilder builder)
      : mode_(mode), type_(type), shading_(shading), edgeSnap_(EpiPass::edgeSnap()) {
    // Highlight knots are the CPU's.
    const bool gpu = !shading_.sliceHighlights && (builder == PstBuilder::Gpu ||
                                                   (builder == PstBuilder::Auto && !gl::rendersOnCpu()));
    const bool sceneVectors = !shading_.sliceVectors && shading_.plan.texture &&
                              shading_.textureMode == TextureMode::Vector;
    if (shading_.scene) {
      static const shading::TextureSet kNoTextures;
      static const shading::EnvironmentSet kNoMaps;
      // The texture array is sampled by direct texturing and by the GPU's
      // vector extraction.
      const bool sampled = shading_.textureMode == TextureMode::Direct || (gpu && sceneVectors);
      materials_.emplace(*shading_.scene, shading_.textures ? *shading_.textures : kNoTextures,
                         shading_.environment ? *shading_.environment : kNoMaps, sampled);
    }
    if (gpu && sceneVectors) {
      const SceneTexturing texturing{shading_.plan.uv, *shading_.textures, *materials_};
      geometry_.emplace(mode, shading_.plan.extraCount, &texturing);
    } else if (gpu) {
      geometry_.emplace(mode, shading_.plan.extraCount);
    }
    if (shading_.sliceVectors) {
      passes_.emplace_back(mode, shading::Pass::Texture, shading_, pulled());
      return;
    }
    if (shading_.plan.mask) passes_.emplace_back(mode, shading::Pass::Texture, shading_, pulled(), /*maskDepth=*/true);
    for (shading::Pass p : shading_.plan.passes()) passes_.emplace_back(mode, p, shading_, pulled());
  }

  bool readsDeviceTable() const override { return pulled(); }

  void rasterize(const ExtremeVertices& v, const SliceTableView& slices, const ShearingCamera& cam,
                 int row, FrameSink& sink, RenderStats& stats) override {
    if (!pulled()) return fill(&v, nullptr, slices, cam, row, sink, stats);
    {
      ScopedStage s(stats.times, "pst");
      uploaded_ = GpuVertices::upload(v);
    }
    fill(&v, &*uploaded_, slices, cam, row, sink, stats);
  }

  void rasterize(const GpuVertices& v, const GpuSliceTable& slices, const ShearingCamera& cam, int row,
                 FrameSink& sink, RenderStats& stats) override {
    if (!pulled()) fail("EPI rasterizer", "this rasterizer builds PSTs on the CPU: it needs host vertices");
    fill(nullptr, &v, slices, cam, row, sink, stats);
  }

 private:
  // Host vertices for the CPU-built PSTs, device vertices for the pulled
  // ones; the other may be null.
  void fill(const ExtremeVertices* host, const GpuVertices* device, const SliceTableView& slices,
            const ShearingCamera& cam, int row, FrameSink& sink, RenderStats& stats) {
    GLint maxSize = 4096;
    gl::GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = cam.views(), w = cam.width(), h = cam.height();
    const int chunkRows = std::min(n, int(maxSize));  // views per tile
    const int chunks = (n + chunkRows - 1) / chunkRows;
    const bool accumulate = passes_.size() > 1;
    const PixelType storage = accumulate ? PixelType::F32 : type_;
    // A batch of scanlines per draw, its framebuffer within the budget;
    // three such batches in flight in the readback ring.
    const size_t bytesPerRow = size_t(w) * (4 * Image::channelBytes(storage) + 4);
    const int budgetRows = int(std::max<size_t>(chunkRows, kTargetBudget / bytesPerRow));
    const int batch = chunks > 1 ? 1 : std::clamp(std::min(int(maxSize), budgetRows) / n, 1, h);
    const RenderTarget& target = targetFor(w, batch * chunkRows, storage);
    const size_t rowBytes = size_t(w) * 4 * Image::channelBytes(type_);
    // Where the sink lends a texture of EPIs (mvr live's screen), each is
    // copied into its layer on the GPU and nothing is read back.
    const GLuint layers = target.copiesBytes() ? sink.epiTexture(row, w, n, type_) : 0;
    std::optional<ReadbackRing> ring;
    if (!layers) ring.emplace(size_t(batch) * n * rowBytes);
    ImagePool pool;
    setDepthConvention();
    target.bind();
    const glm::vec2 scale(2.0f / w, 2.0f / (batch * chunkRows));
    const glm::vec3 eye0(cam.eye(0, row)), eyeStep(cam.eye(1, row) - cam.eye(0, row));
    gl::Enable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    if (materials_) materials_->bind();
    // A share's scanlines sit where the whole render puts them (batches
    // start at multiples of the batch size), so its EPIs are the same bytes.
    const IndexRange lines = cam.share().scanlines;
    for (int first = lines.begin - lines.begin % batch; first < lines.end; first += batch) {
      const int count = std::min(batch, h - first);
      const int own = std::max(first, lines.begin), ownEnd = std::min(first + count, lines.end);
      if (pulled()) {
        // Before the clear: on CPU implementations of GL the build's
        // barriers would otherwise flush the clear of the whole target.
        ScopedStage s(stats.times, "pst");
        gl::GpuClock::mark("pst");
        geometry_->build(*device, slices.device(), first, count, n);
        vectorTexels_ += geometry_->vectorTexels();
        // The build's compute passes use storage bindings of their own.
        if (materials_) materials_->bind();
      }
      // The batch's EPIs, filled chunk by chunk as the ring hands them over.
      std::optional<EpiBatch> epis;
      if (!layers) epis.emplace(sink, pool, row, IndexRange{own, ownEnd}, w, n, type_);
      // A share that owns part of the batch clears and draws only its rows:
      // on a CPU implementation of GL the clear of a whole batch costs as
      // much as filling it.
      const bool part = own > first || ownEnd < first + count;
      if (part) {
        gl::Enable(GL_SCISSOR_TEST);
        gl::Scissor(0, (own - first) * chunkRows, w, (ownEnd - own) * chunkRows);
      }
      for (int c = 0; c < chunks; ++c) {
        const int view0 = c * chunkRows, views = std::min(chunkRows, n - view0);
        gl::GpuClock::mark("clear");
        target.clear();
        gl::GpuClock::mark("draw");
        const Batch b{first, count, n, chunkRows, view0, scale, eye0, eyeStep};
        for (const EpiPass& pass : passes_) drawPass(pass, host, slices, b, stats);
        if (layers) {
          for (int j = own; j < ownEnd; ++j) target.copyRows((j - first) * chunkRows, views, layers, view0, j);
          continue;
        }
        {
          ScopedStage s(stats.times, "readback");
          gl::GpuClock::mark("readback");
          if (views == chunkRows) {
            // The batch's EPIs are stacked without gaps: one read for all.
            ring->readRowRuns(target, (own - first) * chunkRows, views, epis->rows(view0));
          } else {
            for (int j = own; j < ownEnd; ++j)
              ring->readRows(target, (j - first) * chunkRows, views, epis->rows(j - own, view0));
          }
        }
        if (c + 1 < chunks) continue;
        ring->submit([epis = *epis, &sink] { epis.handOn(sink); });
      }
      if (part) gl::Disable(GL_SCISSOR_TEST);
    }
    if (ring) {
      ring->drain();
      stats.times.add("gpu_wait", ring->waitSeconds());
    } else {
      stats.notes["epis"] = "texture";
    }
    gl::Disable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
    // The passes' blending back to GL's defaults: a two-source blend left
    // on made the next renderer's draw into two colour targets (deferred's
    // G-buffer) an INVALID_OPERATION.
    gl::Disable(GL_BLEND);
    gl::BlendFunc(GL_ONE, GL_ZERO);
    gl::ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl::DepthMask(GL_TRUE);
    setDepthConvention();
    gl::checkError("EPI rasterization");
    stats.counters["epis_per_draw"] = batch;
    stats.notes["pst_builder"] = pulled() ? "gpu" : "cpu";
    stats.counters["pst_vertices"] += double(verticesEmitted_);
    if (vectorTexels_) stats.counters["texture_vector_texels"] += double(vectorTexels_);
    verticesEmitted_ = vectorTexels_ = 0;
  }

  // Colour and depth of one batch's framebuffer.
  static constexpr size_t kTargetBudget = size_t(256) << 20;

  // The batch framebuffer, kept from one row (and render) to the next: on
  // a CPU implementation of GL a fresh one cost 0.24 s at 640x480 x 100
  // views, per row of a full-parallax set and per share of a split job.
  const RenderTarget& targetFor(int w, int h, PixelType storage) {
    if (!target_ || target_->width() != w || target_->height() != h || targetStorage_ != storage) {
      target_.reset();  // the old one's memory first
      target_.emplace(w, h, type_, 0, storage);
      targetStorage_ = storage;
    }
    return *target_;
  }

  bool pulled() const { return geometry_.has_value(); }

  // Scanlines [first, first + count), views [view0, view0 + chunkRows) of
  // `views`, stacked chunkRows apart in the framebuffer.
  struct Batch {
    int first, count, views, chunkRows, view0;
    glm::vec2 scale;
    glm::vec3 eye0, eyeStep;
  };

  // One shading pass over the batch: pulled geometry, or geometry emitted
  // here and uploaded.
  void drawPass(const EpiPass& pass, const ExtremeVertices* v, const SliceTableView& slices,
                const Batch& b, RenderStats& stats) {
    if (pulled()) {
      ScopedStage s(stats.times, "raster");
      pass.begin(b.scale, b.eye0, b.eyeStep);
      geometry_->bind(pass.program(), b.chunkRows, b.view0);
      geometry_->draw();
      return;
    }
    {
      ScopedStage s(stats.times, "pst");
      clearGeometry();
      for (int k = 0; k < b.count; ++k)
        emitScanline(pass, *v, slices.host(), b.first + k, b.views, float(k * b.chunkRows - b.view0));
    }
    ScopedStage s(stats.times, "raster");
    pass.begin(b.scale, b.eye0, b.eyeStep);
    gl::Buffer vectors = bindTextures(pass);  // deleted after the draw is issued: GL completes it
    drawGeometry(pass);
  }

  void clearGeometry() {
    vertices_.clear();
    indices_.clear();
    vectors_.clear();
  }

  // Returns the buffer behind the vector texture: it must outlive the draw.
  gl::Buffer bindTextures(const EpiPass& pass) {
    if (!pass.linear()) return {};
    vectorTexels_ += vectors_.texels().size();
    gl::Buffer buffer = gl::makeBuffer(vectors_.texels().data(), std::max<size_t>(1, vectors_.texels().size()));
    vectorTexture_ = gl::Texture::overBuffer(GL_RGBA32F, buffer.id());
    vectorTexture_.bind(EpiPass::kVectorUnit);
    return buffer;
  }

  // yBase: framebuffer row of EPI row coordinate r = 0 for this scanline.
  void emitScanline(const EpiPass& pass, const ExtremeVertices& v, const SliceTable& table, int j,
                    int n, float yBase) {
    for (const Slice& s : table.scanline(j)) {
      auto [e0, e1] = sliceEnds(v, s);
      const Pst pst = makePst(e0, e1, n, v.cullBack[s.triangle]);
      const uint32_t material = v.materials.empty() ? 0 : v.materials[s.triangle];
      const SliceVector vector = pass.linear() ? addVector(v, s.triangle, pst, material) : SliceVector{};
      for (int p = 0; p < pst.pieceCount; ++p) {
        if (vector.knotCount < 2) {
          emitPiece(pass, pst, pst.pieces[p], float(material), vector, nullptr, yBase);
          continue;
        }
        // A split track: one piece per pair of knots.
        const HighlightKnot* knots = v.knots.data() + vector.firstKnot;
        for (int k = 0; k + 1 < vector.knotCount; ++k) {
          PstPiece part = pst.pieces[p];
          part.rTop = std::max(part.rTop, knots[k].r);
          part.rBottom = std::min(part.rBottom, knots[k + 1].r);
          if (part.rTop < part.rBottom) emitPiece(pass, pst, part, float(material), vector, knots + k, yBase);
        }
      }
    }
  }

  // vector: the slice's texture vector in this batch (linear passes);
  // knots: the two highlight knots around this piece, or null.
  void emitPiece(const EpiPass& pass, const Pst& pst, const PstPiece& piece, float material,
                 const SliceVector& vector, const HighlightKnot* knots, float yBase) {
    const int slivers = mode_ == PstMode::Strip ? sliverCount(pst, piece) : 1;
    const float rows[2] = {piece.rTop, piece.rBottom};
    const float iw0 = pst.e0.invW, iw1 = pst.e1.invW;
    const float side = piece.front ? 1.0f : -1.0f;
    const int count = pass.attributeCount(), stride = pass.stride();
    float a0[shading::kMaxExtras], a1[shading::kMaxExtras];
    if (pass.linear()) {
      a0[0] = vector.u0, a1[0] = vector.u1;
      a0[1] = a1[1] = float(vector.base);
      a0[2] = a1[2] = float(vector.length);
      a0[3] = a1[3] = 0.0f;
      for (int k = 0; k < 2 && count > 4; ++k) {
        const HighlightKnot knot = knots ? knots[k] : HighlightKnot{0.0f, glm::vec3(0.0f)};
        const float at[4] = {knot.specular.r, knot.specular.g, knot.specular.b, knot.r};
        std::copy_n(at, 4, a0 + 4 + 4 * k);
        std::copy_n(at, 4, a1 + 4 + 4 * k);
      }
    } else {
      pass.gather(pst.e0, piece.front, a0);
      pass.gather(pst.e1, piece.front, a1);
    }
    // Exact quads widened outward by the snapping margin (EpiPass::edgeSnap).
    const float margin = mode_ == PstMode::Exact
                             ? edgeSnap_ * (1.0f + std::max(std::abs(pst.e0.dx), std::abs(pst.e1.dx))) * side
                             : 0.0f;
    for (int k = 0; k <= slivers; ++k) {
      // Rulings evenly spaced in the 3D parameter s, where attributes are
      // linear; the screen parameter is u = s iw0 / ((1 - s) iw1 + s iw0).
      const float s = float(k) / slivers;
      const float u = k == slivers ? 1.0f : s * iw0 / ((1.0f - s) * iw1 + s * iw0);
      for (float r : rows) {
        const float x = pst.x0(r) + u * pst.width(r) + (2.0f * u - 1.0f) * margin;
        indices_.push_back(uint32_t(vertices_.size() / stride));
        const size_t at = vertices_.size();
        vertices_.resize(at + stride, 0.0f);
        float* out = vertices_.data() + at;
        if (mode_ == PstMode::Exact) {
          // The fragment solves its view and u from its centre and the
          // ends' tracks (epi_pass.cpp): rows from yBase, x0 and dx.
          const float head[16] = {x,        yBase + r,    yBase,        0.0f,         pst.e0.depth, pst.e1.depth,
                                  iw0,      iw1,          side,         material,     0.0f,         0.0f,
                                  pst.e0.x0, pst.e0.dx,   pst.e1.x0,    pst.e1.dx};
          std::copy_n(head, 16, out);
          const int chunk = (stride - 16) / 2;
          std::copy_n(a0, count, out + 16);
          std::copy_n(a1, count, out + 16 + chunk);
        } else {
          const float head[8] = {x, yBase + r, pstDepth(pst, u), r - 0.5f, side, material, 0, 0};
          std::copy_n(head, 8, out);
          if (pass.linear()) {
            // The vector parameter times the slice's width, and the width:
            // both affine in (x, r), so any triangulation interpolates them
            // exactly and their quotient is the exact parameter.
            const float t = a0[0] + (a1[0] - a0[0]) * u, width = pst.width(r);
            const float linear[4] = {t * width, width, a0[1], a0[2]};
            std::copy_n(linear, 4, out + 8);
            std::copy(a0 + 4, a0 + count, out + 12);  // highlight knots: the same at every vertex
            continue;
          }
          // Attributes divided back at the ruling.
          const float invW = iw0 + (iw1 - iw0) * u;
          for (int c = 0; c < count; ++c) out[8 + c] = (a0[c] + (a1[c] - a0[c]) * u) / invW;
        }
      }
    }
    indices_.push_back(kRestart);
  }

  // The slice's 1-D texture vector in this batch's store: its own (image
  // slices), or extracted at the wider p-edge's resolution.
  SliceVector addVector(const ExtremeVertices& v, uint32_t triangle, const Pst& pst, uint32_t material) {
    if (shading_.sliceVectors) {
      SliceVector own = v.vectors.at(triangle);
      own.base = vectors_.append(v.vectorTexels, own.base, own.length);
      return own;
    }
    const int layer = shading_.textures->materialLayers()[material];
    if (layer < 0 || pst.pieceCount == 0) return SliceVector{};
    const int uv = shading_.plan.uv;
    const glm::vec2 uv0(pst.e0.extrasOverW[uv], pst.e0.extrasOverW[uv + 1]);
    const glm::vec2 uv1(pst.e1.extrasOverW[uv], pst.e1.extrasOverW[uv + 1]);
    const float rBottom = pst.pieces[pst.pieceCount - 1].rBottom;
    const float widest = std::max(std::abs(pst.width(0.0f)), std::abs(pst.width(rBottom)));
    const int base = vectors_.add(*shading_.textures, layer, uv0, uv1, pst.e0.invW, pst.e1.invW, widest);
    // An emission texture's vector right after the chain (EpiPass reads it there).
    if (const int glow = shading_.textures->emissionLayers()[material]; glow >= 0)
      vectors_.add(*shading_.textures, glow, uv0, uv1, pst.e0.invW, pst.e1.invW, widest);
    return SliceVector{base, shading::TextureVectors::lengthFor(widest), 0.0f, 1.0f};
  }

  void drawGeometry(const EpiPass& pass) {
    if (indices_.empty()) return;
    verticesEmitted_ += vertices_.size() / pass.stride();
    gl::Buffer vertices = gl::makeBuffer(vertices_.data(), vertices_.size());
    gl::Buffer indices = gl::makeBuffer(indices_.data(), indices_.size());
    pass.bindVertices(vertices.id(), indices.id());
    gl::DrawElements(GL_TRIANGLE_STRIP, GLsizei(indices_.size()), GL_UNSIGNED_INT, nullptr);
  }

  PstMode mode_;
  PixelType type_;
  EpiShading shading_;
  float edgeSnap_;
  std::vector<EpiPass> passes_;
  std::vector<float> vertices_;
  std::vector<uint32_t> indices_;
  shading::TextureVectors vectors_;
  std::optional<shading::GpuMaterials> materials_;  // with a scene
  std::optional<PstGeometry> geometry_;             // PSTs built on the GPU
  std::optional<GpuVertices> uploaded_;             // host vertices, uploaded for it
  gl::Texture vectorTexture_;
  size_t verticesEmitted_ = 0, vectorTexels_ = 0;
  std::optional<RenderTarget> target_;
  PixelType targetStorage_ = PixelType::U8;
};

}  // namespace

std::unique_ptr<EpiRasterizer> makeGlRasterizer(PstMode mode, PixelType type,
                                                const EpiShading& shading, PstBuilder builder) {
  if (mode == PstMode::Cpu || mode == PstMode::Spans) fail("--pst", std::string(pstModeName(mode)) + " is not a GL mode");
  return std::make_unique<GlRasterizer>(mode, type, shading, builder);
}

}  // namespace mvr
