#pragma once
// Source views for the image-based back end (de Quilletes 2018): the
// deferred pipeline rendered from chosen eyes on the camera plane, depth
// peeled into layers, read back with their depth.
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/camera.h"
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

class SourceLayerRenderer {
 public:
  virtual ~SourceLayerRenderer() = default;
  // Up to maxLayers layers seen from eye through cam's image-plane window,
  // stopping at the first empty one or where `filter` says. trackWidth: the
  // width E of the track the layers must serve, for the peeling offset.
  virtual std::vector<SourceLayer> render(const ShearingCamera& cam, const glm::dvec2& eye,
                                          int maxLayers, double trackWidth, RenderStats& stats,
                                          const LayerFilter& filter = {}) = 0;
};

// Needs a current GL context. separateHighlights: the colours leave out
// specular highlights, and normals and materials are read back so that
// the caller can add highlights per view.
std::unique_ptr<SourceLayerRenderer> makeSourceLayerRenderer(const Scene& scene,
                                                             bool separateHighlights = false);

}  // namespace mvr
