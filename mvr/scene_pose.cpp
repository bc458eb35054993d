#include "mvr/scene_pose.h"

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"

namespace mvr {

glm::mat4 turntable(const glm::vec3& pivot, double degrees) {
  // In double, reduced to a turn first: 360 * k / N for large k stays exact
  // where it matters (a whole turn is the identity, to the bit).
  const double turn = std::fmod(degrees, 360.0);
  if (turn == 0.0) return glm::mat4(1.0f);
  const glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(pivot)) *
                       glm::rotate(glm::dmat4(1.0), turn * std::numbers::pi / 180.0, glm::dvec3(0, 1, 0)) *
                       glm::translate(glm::dmat4(1.0), -glm::dvec3(pivot));
  return glm::mat4(m);
}

void poseGeometry(Scene& scene, const Scene& still, const glm::mat4& m) {
  if (scene.vertexCount() != still.vertexCount()) fail("pose", "the scene and its still differ in vertices");
  scene.positions = still.positions;
  scene.normals = still.normals;
  scene.transformGeometry(m);
}

}  // namespace mvr
