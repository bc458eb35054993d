// Deferred shading baseline (as in de Quilletes 2018): per view a G-buffer
// of albedo, normal and depth, then a full-screen pass lights every pixel.
// Lighting is per pixel here, so its images differ slightly from Gouraud.
#include "mvr/backends/deferred/deferred_renderer.h"
#include "mvr/views/deferred_pipeline.h"
#include "mvr/views/view_loop.h"

namespace mvr {
namespace {

class DeferredRenderer final : public Renderer {
 public:
  DeferredRenderer(const Scene& scene, PixelType type) : scene_(scene), type_(type), pipeline_(scene) {}
  std::string name() const override { return "deferred"; }
  bool sceneMoved() override {
    pipeline_.sceneMoved(scene_);
    return true;
  }
  FrameOrder order() const override { return FrameOrder::View; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    RenderTarget target(cam.width(), cam.height(), type_);
    const GBuffer gbuffer = pipeline_.makeGBuffer(cam.width(), cam.height());
    pipeline_.begin(cam.width(), cam.height());
    renderEachView(cam, target, sink, stats, [&](int row, int view) {
      const glm::dmat4 viewProj = cam.viewProjection(view, row);
      {
        ScopedStage s(stats.times, "geometry");
        pipeline_.geometry(viewProj, gbuffer, nullptr);
      }
      ScopedStage s(stats.times, "lighting");
      pipeline_.lighting(viewProj, cam.eye(view, row), gbuffer, target);
    });
    gl::checkError("deferred render");
  }

 private:
  const Scene& scene_;
  PixelType type_;
  DeferredPipeline pipeline_;
};

}  // namespace

std::unique_ptr<Renderer> makeDeferredRenderer(const Scene& scene, PixelType type) {
  return std::make_unique<DeferredRenderer>(scene, type);
}

}  // namespace mvr
