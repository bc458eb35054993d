#pragma once
// Deferred shading (as in de Quilletes 2018): per view a G-buffer of albedo,
// normal and depth, then a full-screen pass lights every pixel. The
// deferred baseline and the image-based back end's source layers share it.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/gl/gl_program.h"
#include "mvr/gl/render_target.h"
#include "mvr/gl/scene_buffers.h"
#include "mvr/scene.h"
#include "mvr/views/fragment_lists.h"
#include "shading/gpu_materials.h"
#include "shading/shading_plan.h"

namespace mvr {

// A G-buffer: albedo (a = 1 marks covered pixels), normal (w: material
// index), depth and, for a scene with emission textures, the emission.
class GBuffer {
 public:
  // exactAlbedo: albedo in float (Scene::exactColors), else 8 bits. glow:
  // a target for the emission per pixel (ShadingPlan::emissionTexture).
  GBuffer(int width, int height, bool exactAlbedo = false, bool glow = false);
  // Depth alone (a coverage pass: no colour is written or kept).
  static GBuffer depthOnly(int width, int height);
  void bindForWriting() const;  // sets the viewport, as RenderTarget::bind
  GLuint depthTexture() const { return depth_.id(); }
  GLuint normalTexture() const { return normal_.id(); }
  void bindForReading() const {
    albedo_.bind(0);
    normal_.bind(1);
    depth_.bind(2);
    if (glow_.id()) glow_.bind(3);
  }

 private:
  struct DepthOnly {};
  GBuffer(int width, int height, DepthOnly);

  int width_, height_;
  gl::Texture albedo_, normal_, depth_, glow_;
  gl::Framebuffer fbo_;
  bool colour_ = true;
};

// The two passes of deferred shading, shared by the baseline and the
// image-based back end's source views.
class DeferredPipeline {
 public:
  // separateHighlights: the lighting pass leaves out specular highlights.
  explicit DeferredPipeline(const Scene& scene, bool separateHighlights = false);

  // Before the passes of a sequence of views of this size. rows: the image
  // rows (window rows, top first) the passes draw; the targets are still
  // cleared whole, so rows outside stay empty. Default: every row.
  void begin(int width, int height, IndexRange rows = {0, -1});
  // The scene moved (mvr/scene_pose.h): lit per pixel, so its new
  // positions and normals are all.
  void sceneMoved(const Scene& scene) { buffers_.move(scene); }
  // The G-buffers this pipeline fills.
  GBuffer makeGBuffer(int width, int height) const {
    return GBuffer(width, height, exactAlbedo_, plan_.emissionTexture);
  }
  // previous: the G-buffer of the layer in front (depth peeling), or null.
  void geometry(const glm::dmat4& viewProj, const GBuffer& gbuffer, const GBuffer* previous,
                const glm::vec4& peel = glm::vec4(0.0f));
  void lighting(const glm::dmat4& viewProj, const glm::dvec3& eye, const GBuffer& gbuffer,
                const RenderTarget& target);
  // Every fragment geometry() would shade (its culling too) into the
  // pipeline's fragment lists, so that resolve() gives each depth-peeled
  // layer without drawing the mesh again. Always drawn (drawOnlyIf does
  // not apply). False when the lists would need more than their memory
  // limit (FragmentLists::setMaxBytes), or the scene has emission textures
  // (the lists keep no emission): draw each layer with geometry().
  bool collect(const glm::dmat4& viewProj);
  // The layer geometry(viewProj, gbuffer, previous, peel) would draw, from
  // the lists of the last collect() of the same view: the same pixels,
  // depths, albedo and normals.
  void resolve(const GBuffer& gbuffer, const GBuffer* previous, const glm::vec4& peel = glm::vec4(0.0f));
  // The nearest surface's depth alone, into a GBuffer::depthOnly target:
  // the geometry pass's coverage (its culling too) without its shading; of
  // the `triangles` alone (indices, three a triangle) where given.
  void depth(const glm::dmat4& viewProj, const GBuffer& target, const std::vector<uint32_t>* triangles = nullptr);
  // The passes that follow draw only if this samples-passed query counted
  // any (conditional rendering: the GPU decides, the CPU does not wait);
  // their clears still happen, so a skipped pass leaves an empty target.
  // 0: always draw.
  void drawOnlyIf(GLuint samplesQuery) { condition_ = samplesQuery; }

 private:
  // The plan's passes as defines: the geometry pass textures, the lighting
  // pass adds highlights.
  std::string header() const;
  // The geometry pass's program; prelude: defines and declarations before
  // its fragment shader (PEEL, COLLECT).
  gl::Program geometryProgram(const char* name, const std::string& prelude) const;

  SceneBuffers buffers_;
  shading::ShadingPlan plan_;
  gl::Program geometry_, peeling_, lighting_, depth_, collect_, resolve_, resolvePeel_;
  FragmentLists lists_;
  gl::VertexArray emptyVao_;
  shading::GpuMaterials materials_;
  bool exactAlbedo_;
  IndexRange rows_{0, -1};  // -1: every row
  GLuint condition_ = 0;    // drawOnlyIf
  int width_ = 0, height_ = 0;
  // Runs a draw restricted to rows_.
  template <class Draw>
  void inRows(Draw&& draw);
};

}  // namespace mvr
