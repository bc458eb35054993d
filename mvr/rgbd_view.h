#pragma once
// One RGB-D reference: a colour image, its depth map and its camera, in
// the convention of ShearingCamera::worldToCamera and intrinsics (OpenCV's
// axes; K maps to pixel coordinates with pixel (i, j)'s centre at
// (i + 0.5, j + 0.5)). What the depth-image warping back end composites,
// whether rendered or read from a capture.
#include <vector>

#include <glm/glm.hpp>

#include "mvr/image.h"

namespace mvr {

// Where the surface a pixel samples ends inside it along its row, found
// by a finer render (PixelOutline, mvr/views/source_layers.h): offsets
// from the pixel's left boundary (below 0 or above 1 where it goes on
// into the empty neighbour's near half) and the camera z there.
// right < 0: not measured.
struct PixelEnds {
  float left = -1.0f, leftZ = 0.0f, right = -1.0f, rightZ = 0.0f;
};

struct RgbdView {
  Image color;       // F32, linear, rows top first
  DepthImage depth;  // camera z (along the view axis), world units; 0: no sample
  // Per pixel, where rendered sources measured them: the silhouette's
  // ends inside pixels beside an empty one. Empty: none (a capture).
  std::vector<PixelEnds> ends;
  glm::dmat3 K{1.0};
  glm::dmat4 V{1.0};  // world to camera

  // The camera's centre in world coordinates.
  glm::dvec3 center() const { return glm::dvec3(glm::inverse(V) * glm::dvec4(0.0, 0.0, 0.0, 1.0)); }
  // Maps (u z, v z, z, 1), pixel coordinates times camera z, to the world
  // point: V^-1 with K^-1 in its upper 3 x 3 first.
  static glm::dmat4 pixelToWorld(const glm::dmat3& K, const glm::dmat4& V) {
    return glm::inverse(V) * glm::dmat4(glm::inverse(K));
  }
};

}  // namespace mvr
