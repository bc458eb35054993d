// Source layers for the image-based back end: the deferred pipeline from a
// chosen eye, depth peeled with de Quilletes' extended offset.
#include "mvr/views/source_layers.h"

#include <algorithm>
#include <optional>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/views/deferred_pipeline.h"
#include "mvr/views/outline_triangles.h"

namespace mvr {
namespace {

// A pixel's outline from its samples at uSamples columns a pixel (a depth
// texture of uSamples x the width), as PixelOutline: the first and last
// covered sample's outer edges and depths, each end kept on its own side
// of the pixel's centre (a covered centre means the silhouette lies
// beyond it; between two sample centres, a quarter sample out), and run
// on over the neighbour's covered samples short of its centre. Kept
// within the pixel, the silhouette of a view beside the source stood up
// to half a pixel inside svr's (bunny 160x120, view 1: 26 pixels short).
const char* const kOutline = R"(
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D uFine;
layout(std430, binding = 0) writeonly buffer Outline { vec4 uOutline[]; };
uniform int uWidth;
uniform int uSamples;
uniform uint uFirst;  // the layer's first pixel in Outline
float fine(int i, int j) { return texelFetch(uFine, ivec2(i, j), 0).r; }
const float kJump = 1.02;
bool sameSurface(float d, float before) { return d != 0.0 && d <= before * kJump; }
void main() {
  int x = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y);
  if (x >= uWidth) return;
  int first = x * uSamples, last = first + uSamples - 1, lo = -1, hi = -1;
  for (int s = first; s <= last; ++s)
    if (fine(s, j) != 0.0) {
      if (lo < 0) lo = s;
      hi = s;
    }
  if (lo < 0) {
    uOutline[uFirst + uint(j * uWidth + x)] = vec4(-1.0, 0.0, -1.0, 0.0);
    return;
  }
  // The run through the samples beside the centre (else the first and
  // last covered) of one surface: covered, and none more than kJump
  // nearer than the one before it (window depth is about 1 / distance; a
  // tilted face changes by far less within a sample). A bar thinner than a
  // pixel beside or in front of it is another object's, whose depth would
  // move the end with it (thin-deep: 5 pixels wide in the next view).
  // Covered from its boundary on, the run goes on over the empty
  // neighbour's near half, where a silhouette its centre misses lies.
  int L = fine(first + (uSamples - 1) / 2, j) != 0.0 ? first + (uSamples - 1) / 2 : lo;
  int R = fine(first + uSamples / 2, j) != 0.0 ? first + uSamples / 2 : hi;
  float dLo = fine(L, j), dHi = fine(R, j);
  int stop = x > 0 ? first - uSamples / 2 : first;
  while (L > stop && sameSurface(fine(L - 1, j), dLo)) dLo = fine(--L, j);
  stop = x + 1 < uWidth ? last + uSamples / 2 : last;
  while (R < stop && sameSurface(fine(R + 1, j), dHi)) dHi = fine(++R, j);
  float n = float(uSamples), quarter = 0.25 / n;
  uOutline[uFirst + uint(j * uWidth + x)] =
      vec4(min(float(L - first) / n, 0.5 - quarter), dLo, max(float(R + 1 - first) / n, 0.5 + quarter), dHi);
}
)";

class SourceLayerRendererImpl final : public SourceLayerRenderer {
 public:
  SourceLayerRendererImpl(const Scene& scene, bool separateHighlights, int outlineSamples, Peeling peeling)
      : scene_(scene),
        pipeline_(scene, separateHighlights),
        normals_(separateHighlights),
        outlineSamples_(outlineSamples),
        peeling_(peeling) {
    if (outlineSamples_ > 1) outline_ = gl::linkProgram("source-outline", {{GL_COMPUTE_SHADER, gl::glslHeader() + kOutline}});
  }

  std::vector<SourceLayer> render(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers,
                                  double trackWidth, RenderStats& stats,
                                  const LayerFilter& filter) override {
    const int w = cam.width(), h = cam.height();
    const Peel peel = [&] {
      ScopedStage s(stats.times, "acquire");
      return start(cam, eye, maxLayers, trackWidth, stats);
    }();
    Queries queries(1);
    std::vector<SourceLayer> layers;
    for (int k = 0; k < maxLayers; ++k) {
      GLuint samples = 0;
      const GBuffer* gbuffer = nullptr;
      {
        ScopedStage s(stats.times, "acquire");
        gbuffer = &drawLayer(peel, k, queries[0], 0, stats);
        // Each layer is read back and judged before the next: waiting is
        // no loss here.
        gl::GetQueryObjectuiv(queries[0], GL_QUERY_RESULT, &samples);
        if (samples == 0) break;  // an empty layer: nothing lies further back
      }
      SourceLayer layer{eye, k, Image(), std::vector<float>(size_t(w) * h), long(samples)};
      {
        ScopedStage s(stats.times, "acquire");
        layer.color = targets_->color.read();
        gl::GetTextureSubImage(gbuffer->depthTexture(), 0, 0, 0, 0, w, h, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                               GLsizei(layer.depth.size() * sizeof(float)), layer.depth.data());
        if (normals_) {
          layer.normals.resize(size_t(w) * h);
          gl::GetTextureSubImage(gbuffer->normalTexture(), 0, 0, 0, 0, w, h, 1, GL_RGBA, GL_FLOAT,
                                 GLsizei(layer.normals.size() * sizeof(glm::vec4)), layer.normals.data());
        }
      }
      if (filter && !filter(layers, layer)) break;
      layers.push_back(std::move(layer));
    }
    if (!layers.empty() && samplesFor(w) > 1) {
      ScopedStage s(stats.times, "outline");  // its own stage: what the finer outline costs
      // Only the pixels a slicer reads, from the triangles that reach them.
      const std::vector<uint8_t> read = outlinePixels(layers[0].depth, w, h);
      const std::vector<uint32_t> triangles = outlineTriangles(scene_, peel.viewProj, w, h, read);
      stats.counters["outline_triangles"] += double(triangles.size() / 3);
      const gl::Buffer outline = gl::makeBuffer<PixelOutline>(nullptr, size_t(w) * h);
      drawOutline(cam, peel, outline.id(), 0, &triangles);
      std::vector<PixelOutline>& o = layers[0].outline;
      o.resize(size_t(w) * h);
      outline.read(0, GLsizeiptr(o.size() * sizeof(PixelOutline)), o.data());
      for (size_t p = 0; p < o.size(); ++p)
        if (!read[p]) o[p] = PixelOutline{};  // not made from all of its samples' triangles
    }
    gl::checkError("source layers");
    return layers;
  }

  int render(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers, double trackWidth,
             RenderStats& stats, DeviceLayers& store) override {
    if (normals_) fail("source layers", "highlights kept apart need layers read back");
    ScopedStage s(stats.times, "acquire");
    const Peel peel = start(cam, eye, maxLayers, trackWidth, stats);
    // Every layer is issued at once, each drawn only if the one in front
    // had samples (the GPU's test): asking the CPU after each layer would
    // stall the GPU between layers. A layer behind an empty one is empty
    // (the peel discards where nothing lies in front), so the empty tail
    // is cut once the counts are in.
    Queries queries(maxLayers);
    const int first = store.count();
    for (int k = 0; k < maxLayers; ++k) {
      const GBuffer& gbuffer = drawLayer(peel, k, queries[k], k ? queries[k - 1] : 0, stats);
      store.append(eye, targets_->color.colorTexture(), gbuffer.depthTexture());
    }
    int added = 0;
    for (GLuint samples = 1; added < maxLayers && samples; added += samples ? 1 : 0)
      gl::GetQueryObjectuiv(queries[added], GL_QUERY_RESULT, &samples);
    store.truncate(first + added);
    if (added > 0 && samplesFor(cam.width()) > 1) {
      drawOutline(cam, peel, store.outlineBuffer(), uint32_t(size_t(first) * store.pixelsPerLayer()));
      store.markOutlined(first);
    }
    gl::checkError("source layers");
    return added;
  }

 private:
  // Samples-passed queries, one a layer.
  struct Queries {
    explicit Queries(int n) : ids(size_t(n)) { gl::CreateQueries(GL_SAMPLES_PASSED, n, ids.data()); }
    ~Queries() { gl::DeleteQueries(GLsizei(ids.size()), ids.data()); }
    GLuint operator[](int k) const { return ids[size_t(k)]; }
    std::vector<GLuint> ids;
  };

  // What every layer of one eye's peel shares.
  struct Peel {
    glm::dmat4 viewProj;
    glm::dvec3 eye;
    glm::vec4 offset;  // the peeling shader's uPeel
    bool lists;        // the layers come from the pipeline's fragment lists
  };
  // Counts the lists' pass of the mesh in stats (layer_mesh_passes).
  Peel start(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers, double trackWidth, RenderStats& stats) {
    const int w = cam.width(), h = cam.height();
    targets(w, h);
    pipeline_.begin(w, h, cam.share().scanlines);  // a share's scanlines need only those rows
    const CameraSpec& spec = cam.spec();
    Peel p{cam.viewProjectionAt(eye.x, eye.y), glm::dvec3(eye, spec.distance),
           glm::vec4(spec.nearDistance, spec.farDistance, cam.planeWidth() / (w * spec.distance), trackWidth),
           false};
    // One layer is one pass either way; the lists pay from two on.
    p.lists = peeling_ == Peeling::OnePass && maxLayers > 1 && pipeline_.collect(p.viewProj);
    if (p.lists) stats.counters["layer_mesh_passes"] += 1;
    return p;
  }

  // Depth-peeled layer k, its samples counted by `query`, drawn only if
  // `onlyIf` (a query; 0: always) counted any, and lit only if it has
  // samples itself (the GPU decides; an empty layer is never used): its
  // depth in the returned G-buffer, its lit colour in targets_->color. A
  // pass of the mesh is counted in stats (layer_mesh_passes).
  const GBuffer& drawLayer(const Peel& p, int k, GLuint query, GLuint onlyIf, RenderStats& stats) {
    Targets& t = *targets_;
    const GBuffer& gbuffer = t.gbuffers[k % 2];
    const GBuffer* previous = k ? &t.gbuffers[(k + 1) % 2] : nullptr;
    pipeline_.drawOnlyIf(onlyIf);
    gl::BeginQuery(GL_SAMPLES_PASSED, query);
    if (p.lists) {
      pipeline_.resolve(gbuffer, previous, p.offset);
    } else {
      pipeline_.geometry(p.viewProj, gbuffer, previous, p.offset);
      stats.counters["layer_mesh_passes"] += 1;  // issued (the GPU may skip it)
    }
    gl::EndQuery(GL_SAMPLES_PASSED);
    pipeline_.drawOnlyIf(query);
    pipeline_.lighting(p.viewProj, p.eye, gbuffer, t.color);
    pipeline_.drawOnlyIf(0);
    return gbuffer;
  }

  // Samples a pixel the outline of a view w pixels wide gets: the option,
  // within the GL's largest viewport (1: none).
  int samplesFor(int w) const {
    if (outlineSamples_ <= 1) return 1;
    GLint dims[2] = {0, 0};
    gl::GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    return std::max(1, std::min(outlineSamples_, dims[0] / std::max(1, w)));
  }

  // The nearest layer's outline (PixelOutline per pixel) into `buffer`
  // from pixel `first` on: its geometry (or those `triangles` alone)
  // drawn once more at samplesFor(w) columns a pixel, each pixel's samples
  // reduced on the GPU. The peel's later layers need only the nearest, so
  // this comes last; the next peel's start() begins the pipeline at its
  // own width again.
  void drawOutline(const ShearingCamera& cam, const Peel& p, GLuint buffer, uint32_t first,
                   const std::vector<uint32_t>* triangles = nullptr) {
    const int w = cam.width(), h = cam.height(), n = samplesFor(w);
    if (!fine_ || fine_->width != n * w || fine_->height != h) fine_.emplace(n * w, h);
    pipeline_.begin(n * w, h, cam.share().scanlines);
    pipeline_.drawOnlyIf(0);
    pipeline_.depth(p.viewProj, fine_->gbuffer, triangles);
    gl::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    outline_.use();
    gl::setUniform(outline_, "uWidth", w);
    gl::setUniform(outline_, "uSamples", n);
    gl::setUniform(outline_, "uFirst", GLuint(first));
    gl::bindTexture(0, fine_->gbuffer.depthTexture());
    gl::bindStorage(0, buffer);
    gl::dispatch(uint32_t((w + 63) / 64), uint32_t(h), 1, GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }

  struct Fine {
    Fine(int w, int h) : width(w), height(h), gbuffer(GBuffer::depthOnly(w, h)) {}
    int width, height;
    GBuffer gbuffer;
  };

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

  const Scene& scene_;
  DeferredPipeline pipeline_;
  bool normals_;
  int outlineSamples_;
  Peeling peeling_;
  gl::Program outline_;
  std::optional<Targets> targets_;
  std::optional<Fine> fine_;  // the outline's G-buffer
};

}  // namespace

void DeviceLayers::reset(int width, int height, int capacity) {
  eyes_.clear();
  outlined_.clear();
  limit_ = capacity;
  if (width == width_ && height == height_) return;
  width_ = width, height_ = height;
  allocated_ = 0;
  color_ = gl::Buffer(), depth_ = gl::Buffer(), outline_ = gl::Buffer();
}

// Room for `layers` layers, the ones held copied over on the GPU.
void DeviceLayers::grow(int layers) {
  const size_t pixels = pixelsPerLayer(), held = pixels * size_t(count());
  gl::Buffer color = gl::makeBuffer<glm::vec4>(nullptr, pixels * layers);
  gl::Buffer depth = gl::makeBuffer<float>(nullptr, pixels * layers);
  gl::Buffer outline = gl::makeBuffer<PixelOutline>(nullptr, pixels * layers);
  if (held > 0) {
    gl::CopyNamedBufferSubData(color_.id(), color.id(), 0, 0, GLsizeiptr(held * sizeof(glm::vec4)));
    gl::CopyNamedBufferSubData(depth_.id(), depth.id(), 0, 0, GLsizeiptr(held * sizeof(float)));
    gl::CopyNamedBufferSubData(outline_.id(), outline.id(), 0, 0, GLsizeiptr(held * sizeof(PixelOutline)));
  }
  color_ = std::move(color), depth_ = std::move(depth), outline_ = std::move(outline);
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
  outlined_.push_back(0);
}

void DeviceLayers::markOutlined(int layer) {
  if (layer < 0 || layer >= count()) fail("layer store", "no layer " + std::to_string(layer));
  outlined_[size_t(layer)] = 1;
}

void DeviceLayers::truncate(int count) {
  if (count < 0 || count > this->count()) fail("layer store", "cannot keep " + std::to_string(count) + " layers");
  eyes_.resize(size_t(count));
  outlined_.resize(size_t(count));
}

Image DeviceLayers::readColor(int layer) const {
  if (layer < 0 || layer >= count()) fail("layer store", "no layer " + std::to_string(layer));
  Image image(width_, height_, PixelType::F32);
  const size_t bytes = pixelsPerLayer() * sizeof(glm::vec4);
  color_.read(GLintptr(size_t(layer) * bytes), GLsizeiptr(bytes), image.bytes.data());
  return image;
}

std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene, bool separateHighlights,
                                                             int outlineSamples, Peeling peeling) {
  return std::make_unique<SourceLayerRendererImpl>(scene, separateHighlights, outlineSamples, peeling);
}

}  // namespace mvr
