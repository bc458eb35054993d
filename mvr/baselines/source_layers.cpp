// Source layers for the image-based back end: the deferred pipeline from a
// chosen eye, depth peeled with de Quilletes' extended offset.
#include "mvr/baselines/source_layers.h"

#include <optional>

#include "mvr/baselines/deferred_pipeline.h"

namespace mvr {
namespace {

class SourceLayerRendererImpl final : public SourceLayerRenderer {
 public:
  SourceLayerRendererImpl(const Scene& scene, bool separateHighlights)
      : pipeline_(scene, separateHighlights), normals_(separateHighlights) {}

  std::vector<SourceLayer> render(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers,
                                  double trackWidth, RenderStats& stats,
                                  const LayerFilter& filter) override {
    const int w = cam.width(), h = cam.height();
    Targets& t = targets(w, h);
    const RenderTarget& target = t.color;
    const GBuffer* gbuffers = t.gbuffers;
    pipeline_.begin(w, h);
    const glm::dmat4 viewProj = cam.viewProjectionAt(eye.x, eye.y);
    const CameraSpec& spec = cam.spec();
    const glm::vec4 peel(spec.nearDistance, spec.farDistance,
                         cam.planeWidth() / (w * spec.distance), trackWidth);
    GLuint query = 0;
    gl::CreateQueries(GL_SAMPLES_PASSED, 1, &query);
    std::vector<SourceLayer> layers;
    for (int k = 0; k < maxLayers; ++k) {
      const GBuffer& gbuffer = gbuffers[k % 2];
      GLuint samples = 0;
      {
        ScopedStage s(stats.times, "acquire");
        gl::BeginQuery(GL_SAMPLES_PASSED, query);
        pipeline_.geometry(viewProj, gbuffer, k ? &gbuffers[(k + 1) % 2] : nullptr, peel);
        gl::EndQuery(GL_SAMPLES_PASSED);
        gl::GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
      }
      if (samples == 0) break;  // an empty layer: nothing lies further back
      SourceLayer layer{eye, k, Image(), std::vector<float>(size_t(w) * h), long(samples)};
      {
        ScopedStage s(stats.times, "acquire");
        pipeline_.lighting(viewProj, glm::dvec3(eye, spec.distance), gbuffer, target);
        layer.color = target.read();
        gl::GetTextureSubImage(gbuffer.depthTexture(), 0, 0, 0, 0, w, h, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                               GLsizei(layer.depth.size() * sizeof(float)), layer.depth.data());
        if (normals_) {
          layer.normals.resize(size_t(w) * h);
          gl::GetTextureSubImage(gbuffer.normalTexture(), 0, 0, 0, 0, w, h, 1, GL_RGBA, GL_FLOAT,
                                 GLsizei(layer.normals.size() * sizeof(glm::vec4)), layer.normals.data());
        }
      }
      if (filter && !filter(layers, layer)) break;
      layers.push_back(std::move(layer));
    }
    gl::DeleteQueries(1, &query);
    gl::checkError("source layers");
    return layers;
  }

 private:
  // Kept across calls (every source eye of every row has the same size).
  struct Targets {
    Targets(int w, int h) : color(w, h, PixelType::F32), gbuffers{GBuffer(w, h), GBuffer(w, h)} {}
    RenderTarget color;
    GBuffer gbuffers[2];  // ping-pong: the layer in front is read while the next is written
  };
  Targets& targets(int w, int h) {
    if (!targets_ || targets_->color.width() != w || targets_->color.height() != h) targets_.emplace(w, h);
    return *targets_;
  }

  DeferredPipeline pipeline_;
  bool normals_;
  std::optional<Targets> targets_;
};

}  // namespace

std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene,
                                                             bool separateHighlights) {
  return std::make_unique<SourceLayerRendererImpl>(scene, separateHighlights);
}

}  // namespace mvr
