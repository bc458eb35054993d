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

std::vector<double> framingTimes(const Scene& scene, const std::string& clip, size_t most) {
  std::vector<double> keys;
  for (const auto& a : scene.animations) {
    // The clips poseAnimations plays: every one, or the first so named.
    const int index = clip.empty() ? -1 : a->clipNamed(clip);
    if (!clip.empty() && index < 0) continue;
    for (size_t c = 0; c < a->clips.size(); ++c) {
      if (index >= 0 && int(c) != index) continue;
      for (const AnimationChannel& channel : a->clips[c].channels)
        keys.insert(keys.end(), channel.times.begin(), channel.times.end());
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<double> times;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0) times.push_back(0.5 * (keys[i - 1] + keys[i]));
    times.push_back(keys[i]);
  }
  if (times.size() <= most || most < 2) return times;
  std::vector<double> spread(most);
  for (size_t i = 0; i < most; ++i) spread[i] = times[i * (times.size() - 1) / (most - 1)];
  return spread;
}

}  // namespace mvr
