#pragma once
// Source views for the image-based back end (de Quilletes 2018): the
// deferred pipeline rendered from chosen eyes on the camera plane, depth
// peeled into layers, read back with their depth.
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/image.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr {

struct SourceLayer {
  glm::dvec2 eye{0.0};        // camera x, y on the camera plane
  int layer = 0;              // 0 is the nearest
  Image color;                // F32, rows top first (window row 0 on top)
  std::vector<float> depth;   // window depth, reversed Z: 0 where empty
  long fragments = 0;         // samples that passed into this layer
  // With separate highlights: per pixel the world normal of the side seen
  // (xyz) and the material index (w); empty otherwise.
  std::vector<glm::vec4> normals;
};

// Sees each layer as it is read back, with the nearer ones, and may drop
// pixels from it (depth 0); false drops the layer and ends the peeling.
using LayerFilter = std::function<bool(const std::vector<SourceLayer>& nearer, SourceLayer& layer)>;

// Source layers left in GPU memory for a GPU slicer
// (slicing/gpu/gpu_image_slicer.h): layer after layer, each width x height
// pixels in image row order (window row 0 first), never read back.
class DeviceLayers {
 public:
  // Empties the store for up to `capacity` layers of width x height; GPU
  // memory grows with the layers appended and is kept across resets of
  // the same size. Needs a current GL context.
  void reset(int width, int height, int capacity);
  int width() const { return width_; }
  int height() const { return height_; }
  int count() const { return int(eyes_.size()); }
  const glm::dvec2& eye(int layer) const { return eyes_[layer]; }
  GLuint colorBuffer() const { return color_.id(); }  // vec4 per pixel, alpha 1 where covered
  GLuint depthBuffer() const { return depth_.id(); }  // window depth, reversed Z: 0 where empty
  size_t pixelsPerLayer() const { return size_t(width_) * height_; }
  // Copies one layer in on the GPU: a colour and a depth texture of the
  // store's size. Throws mvr::Error when the store is full.
  void append(const glm::dvec2& eye, GLuint colorTexture, GLuint depthTexture);
  // Drops the layers from `count` on (their memory is kept).
  void truncate(int count);
  // One layer's colour read back (F32, rows top first).
  Image readColor(int layer) const;

 private:
  void grow(int layers);

  int width_ = 0, height_ = 0, limit_ = 0, allocated_ = 0;
  std::vector<glm::dvec2> eyes_;
  gl::Buffer color_, depth_;
};

class SourceLayerRenderer {
 public:
  virtual ~SourceLayerRenderer() = default;
  // Up to maxLayers layers seen from eye through cam's image-plane window,
  // stopping at the first empty one or where `filter` says. Only the rows
  // of cam's share of scanlines are drawn; the others are left empty.
  // trackWidth: the width E of the track the layers must serve, for the
  // peeling offset.
  virtual std::vector<SourceLayer> render(const ShearingCamera& cam, const glm::dvec2& eye,
                                          int maxLayers, double trackWidth, RenderStats& stats,
                                          const LayerFilter& filter = {}) = 0;
  // The same layers (no filter), appended to a store in GPU memory instead
  // of read back, the CPU waiting once for their sample counts instead of
  // after each; returns how many were added.
  virtual int render(const ShearingCamera& cam, const glm::dvec2& eye, int maxLayers,
                     double trackWidth, RenderStats& stats, DeviceLayers& store) = 0;
};

// Needs a current GL context. separateHighlights: the colours leave out
// specular highlights, and normals and materials are read back so that
// the caller can add highlights per view.
std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene,
                                                             bool separateHighlights = false);

}  // namespace mvr
