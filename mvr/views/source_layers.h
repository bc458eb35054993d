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
#include "mvr/views/outline_triangles.h"

namespace mvr {

// Where the samples of a pixel that a finer render covered begin and end
// (offsets across the pixel, 0 its left boundary, 1 its right) and the
// window depth of the outermost sample on each side: the silhouette within
// the pixel and the surface point beside it. A pixel whose centre is
// covered gets ends on its own side of the centre (left below 0.5, right
// above); covered up to its boundary, its ends go on over the covered
// samples of the neighbour's near half (left down to -0.5, right up to
// 1.5), where a silhouette the neighbour's centre misses lies.
// right < 0: no sample covered.
struct PixelOutline {
  float left = -1.0f, leftDepth = 0.0f, right = -1.0f, rightDepth = 0.0f;
};

struct SourceLayer {
  glm::dvec2 eye{0.0};        // camera x, y on the camera plane
  int layer = 0;              // 0 is the nearest
  Image color;                // F32, rows top first (window row 0 on top)
  std::vector<float> depth;   // window depth, reversed Z: 0 where empty
  long fragments = 0;         // samples its pass counted (peeled: overdraw too); 0: empty
  // With separate highlights: per pixel the world normal of the side seen
  // (xyz) and the material index (w); empty otherwise.
  std::vector<glm::vec4> normals;
  // The nearest layer's outline within its pixels, per pixel, where the
  // renderer samples it finer (makeSourceLayerRenderer's outlineSamples);
  // empty otherwise and for the layers behind. Only the pixels a slicer
  // reads have one (covered beside an empty pixel, outlineRead: outlinePixels in
  // mvr/views/outline_triangles.h); the others hold PixelOutline{}.
  std::vector<PixelOutline> outline;
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
  // PixelOutline per pixel of the layers that have one (outlined(layer)).
  GLuint outlineBuffer() const { return outline_.id(); }
  bool outlined(int layer) const { return outlined_[size_t(layer)] != 0; }
  size_t pixelsPerLayer() const { return size_t(width_) * height_; }
  // Copies one layer in on the GPU: a colour and a depth texture of the
  // store's size. Throws mvr::Error when the store is full.
  void append(const glm::dvec2& eye, GLuint colorTexture, GLuint depthTexture);
  // Marks a layer whose outline the caller has written into
  // outlineBuffer() at its pixels.
  void markOutlined(int layer);
  // Drops the layers from `count` on (their memory is kept).
  void truncate(int count);
  // One layer's colour read back (F32, rows top first).
  Image readColor(int layer) const;

 private:
  void grow(int layers);

  int width_ = 0, height_ = 0, limit_ = 0, allocated_ = 0;
  std::vector<glm::dvec2> eyes_;
  std::vector<uint8_t> outlined_;
  gl::Buffer color_, depth_, outline_;
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

// How the layers behind the nearest are found. OnePass: the mesh drawn
// once into per-pixel fragment lists (mvr/views/fragment_lists.h),
// each layer picked from them; where the lists would not fit their memory
// limit, one pass a layer. PassPerLayer: depth peeling proper, the mesh
// drawn once a layer. Both give the same layers.
enum class Peeling { OnePass, PassPerLayer };

// Needs a current GL context. separateHighlights: the colours leave out
// specular highlights, and normals and materials are read back so that
// the caller can add highlights per view. outlineSamples > 1: the nearest
// layer's outline is sampled that many columns a pixel (its geometry
// drawn once more at that width) and kept with it (SourceLayer::outline,
// DeviceLayers::outlined).
std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene,
                                                             bool separateHighlights = false,
                                                             int outlineSamples = 1,
                                                             Peeling peeling = Peeling::OnePass);

}  // namespace mvr
