#pragma once
// One RGB-D reference: a colour image, its depth map and its camera, in
// the convention of ShearingCamera::worldToCamera and intrinsics (OpenCV's
// axes; K maps to pixel coordinates with pixel (i, j)'s centre at
// (i + 0.5, j + 0.5)). What the depth-image warping back end composites,
// whether rendered or read from a capture.
#include <glm/glm.hpp>

#include "mvr/image.h"

namespace mvr {

struct RgbdView {
  Image color;       // F32, linear, rows top first
  DepthImage depth;  // camera z (along the view axis), world units; 0: no sample
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
