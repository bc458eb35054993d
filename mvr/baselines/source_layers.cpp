// Source layers for the image-based back end: the deferred pipeline from a
// chosen eye, depth peeled with de Quilletes' extended offset.
#include "mvr/baselines/source_layers.h"

#include <optional>

#include "mvr/baselines/deferred_pipeline.h"
#include "mvr/error.h"

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
    std::vector<SourceLayer> layers;
    peel(cam, eye, maxLayers, trackWidth, stats, [&](int k, long samples, const GBuffer& gbuffer) {
      SourceLayer layer{eye, k, Image(), std::vector<float>(size_t(w) * h), samples};
      {
        ScopedStage s(stats.times, "acquire");
        layer.color = targets_->color.read();
        gl::GetTextureSubImage(gbuffer.depthTexture(), 0, 0, 0, 0, w, h, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                               GLsizei(layer.depth.size() * sizeof(float)), layer.depth.data());
        if (normals_) {
          layer.normals.resize(size_t(w) * h);
          gl::GetTextureSubImage(gbuffer.normalTexture(), 0, 0, 0, 0, w, h, 1, GL_RGBA, GL_FLOAT,
                                 GLsizei(layer.normals.size() * sizeof(glm::vec4)), layer.normals.data());
        }
      }
      if (filter && !filter(layers, layer)) return false;
      layers.push_back(std::move(layer));
      return true;
    });
    return layers;
  }

  int render(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers, double trackWidth,
             RenderStats& stats, DeviceLayers& store) override {
    if (normals_) fail("source layers", "highlights kept apart need layers read back");
    int added = 0;
    peel(cam, eye, maxLayers, trackWidth, stats, [&](int, long, const GBuffer& gbuffer) {
      ScopedStage s(stats.times, "acquire");
      store.append(eye, targets_->color.colorTexture(), gbuffer.depthTexture());
      ++added;
      return true;
    });
    return added;
  }

 private:
  // Renders and lights up to maxLayers depth-peeled layers and hands each
  // (index, samples, its G-buffer; the lit colour in targets_->color) to
  // `take`, which returns false to stop.
  template <class Take>
  void peel(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers, double trackWidth,
            RenderStats& stats, Take&& take) {
    const int w = cam.width(), h = cam.height();
    Targets& t = targets(w, h);
    pipeline_.begin(w, h, cam.share().scanlines);  // a share's scanlines need only those rows
    const glm::dmat4 viewProj = cam.viewProjectionAt(eye.x, eye.y);
    const CameraSpec& spec = cam.spec();
    const glm::vec4 peel(spec.nearDistance, spec.farDistance,
                         cam.planeWidth() / (w * spec.distance), trackWidth);
    GLuint query = 0;
    gl::CreateQueries(GL_SAMPLES_PASSED, 1, &query);
    for (int k = 0; k < maxLayers; ++k) {
      const GBuffer& gbuffer = t.gbuffers[k % 2];
      GLuint samples = 0;
      {
        ScopedStage s(stats.times, "acquire");
        gl::BeginQuery(GL_SAMPLES_PASSED, query);
        pipeline_.geometry(viewProj, gbuffer, k ? &t.gbuffers[(k + 1) % 2] : nullptr, peel);
        gl::EndQuery(GL_SAMPLES_PASSED);
        gl::GetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
        if (samples == 0) break;  // an empty layer: nothing lies further back
        pipeline_.lighting(viewProj, glm::dvec3(eye, spec.distance), gbuffer, t.color);
      }
      if (!take(k, long(samples), gbuffer)) break;
    }
    gl::DeleteQueries(1, &query);
    gl::checkError("source layers");
  }

  // Kept across calls (every source eye of every row has the same size).
  struct Targets {
    Targets(int w, int h, const DeferredPipeline& p)
        : color(w, h, PixelType::F32), gbuffers{p.makeGBuffer(w, h), p.makeGBuffer(w, h)} {}
    RenderTarget color;
    GBuffer gbuffers[2];  // ping-pong: the layer in front is read while the next is written
  };
  Targets& targets(int w, int h) {
    if (!targets_ || targets_->color.width() != w || targets_->color.height() != h) targets_.emplace(w, h, pipeline_);
    return *targets_;
  }

  DeferredPipeline pipeline_;
  bool normals_;
  std::optional<Targets> targets_;
};

}  // namespace

void DeviceLayers::reset(int width, int height, int capacity) {
  eyes_.clear();
  limit_ = capacity;
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  allocated_ = 0;
  color_ = gl::Buffer(), depth_ = gl::Buffer();
}

// Room for `layers` layers, the ones held copied over on the GPU.
void DeviceLayers::grow(int layers) {
  const size_t pixels = pixelsPerLayer(), held = pixels * size_t(count());
  gl::Buffer color = gl::makeBuffer<glm::vec4>(nullptr, pixels * layers);
  gl::Buffer depth = gl::makeBuffer<float>(nullptr, pixels * layers);
  if (held > 0) {
    gl::CopyNamedBufferSubData(color_.id(), color.id(), 0, 0, GLsizeiptr(held * sizeof(glm::vec4)));
    gl::CopyNamedBufferSubData(depth_.id(), depth.id(), 0, 0, GLsizeiptr(held * sizeof(float)));
  }
  color_ = std::move(color), depth_ = std::move(depth);
  allocated_ = layers;
  gl::checkError("allocating the layer store");
}

void DeviceLayers::append(const glm::dvec2& eye, GLuint colorTexture, GLuint depthTexture) {
  if (count() >= limit_) fail("layer store", "full: " + std::to_string(limit_) + " layers");
  // Grown by doubling, so that a scene that peels few layers never holds
  // room for the most it might.
  if (count() >= allocated_) grow(std::min(limit_, std::max(2, 2 * allocated_)));
  const size_t pixels = pixelsPerLayer(), at = size_t(count()) * pixels;
  // Into the buffers on the GPU: with a pack buffer bound, the pointer
  // argument is an offset into it.
  gl::BindBuffer(GL_PIXEL_PACK_BUFFER, color_.id());
  gl::GetTextureSubImage(colorTexture, 0, 0, 0, 0, width_, height_, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(pixels * sizeof(glm::vec4)),
                         reinterpret_cast<void*>(at * sizeof(glm::vec4)));
  gl::BindBuffer(GL_PIXEL_PACK_BUFFER, depth_.id());
  gl::GetTextureSubImage(depthTexture, 0, 0, 0, 0, width_, height_, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                         GLsizei(pixels * sizeof(float)), reinterpret_cast<void*>(at * sizeof(float)));
  gl::BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  eyes_.push_back(eye);
}

Image DeviceLayers::readColor(int layer) const {
  if (layer < 0 || layer >= count()) fail("layer store", "no layer " + std::to_string(layer));
  Image image(width_, height_, PixelType::F32);
  const size_t bytes = pixelsPerLayer() * sizeof(glm::vec4);
  gl::GetNamedBufferSubData(color_.id(), GLintptr(size_t(layer) * bytes), GLsizeiptr(bytes), image.bytes.data());
  return image;
}

std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene,
                                                             bool separateHighlights) {
  return std::make_unique<SourceLayerRendererImpl>(scene, separateHighlights);
}

}  // namespace mvr
