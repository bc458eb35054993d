#pragma once
// An axis-aligned box in world coordinates: what a scene spans and what
// a camera is framed on (CameraSpec::frame).
#include <limits>

#include <glm/glm.hpp>

namespace mvr {

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 center() const { return 0.5f * (min + max); }
  // Bounds of nothing yet: the first point included sets them.
  static Bounds none() {
    return {glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
  }
  void include(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
};

}  // namespace mvr
