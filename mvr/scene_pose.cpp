#include "mvr/scene_pose.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/scene_animation.h"

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
  scene.fromFile = m * still.fromFile;  // a turntable's turn: the frame's cameras see the file turned
}

void poseAnimations(Scene& scene, double t, const std::string& clip, const glm::mat4& after) {
  for (const auto& a : scene.animations) {
    const int index = clip.empty() ? -1 : a->clipNamed(clip);
    if (!clip.empty() && index < 0) {
      a->pose(scene.positions, scene.normals, 0.0, -2, after);  // no clip of this file plays: its rest pose
      continue;
    }
    a->pose(scene.positions, scene.normals, t, index, after);
  }
}

double animationLength(const Scene& scene, const std::string& clip) {
  double d = 0.0;
  for (const auto& a : scene.animations) {
    const int index = clip.empty() ? -1 : a->clipNamed(clip);
    if (clip.empty() || index >= 0) d = std::max(d, a->duration(index));
  }
  return d;
}

bool hasClip(const Scene& scene, const std::string& clip) {
  for (const auto& a : scene.animations)
    if (a->clipNamed(clip) >= 0) return true;
  return false;
}

}  // namespace mvr
