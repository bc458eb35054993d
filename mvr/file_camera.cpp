#include "mvr/file_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"

namespace mvr {
namespace {

const FileCamera& pick(const Scene& scene, const std::string& which) {
  if (scene.fileCameras.empty()) fail("--camera", scene.source + " holds no camera");
  for (const FileCamera& c : scene.fileCameras)
    if (c.name == which) return c;
  char* end = nullptr;
  const long index = std::strtol(which.c_str(), &end, 10);
  if (!which.empty() && *end == '\0' && index >= 0 && size_t(index) < scene.fileCameras.size())
    return scene.fileCameras[size_t(index)];
  std::string names;
  for (const FileCamera& c : scene.fileCameras) names += (names.empty() ? "'" : ", '") + c.name + "'";
  fail("--camera", "'" + which + "' is neither a camera of " + scene.source + " (" + names + ") nor an index below " +
                       std::to_string(scene.fileCameras.size()));
}

// The camera's placement without scale: its axes made orthonormal.
glm::dmat4 rigid(const glm::mat4& toWorld) {
  const glm::dmat4 m(toWorld);
  const glm::dvec3 z = glm::normalize(glm::dvec3(m[2]));
  const glm::dvec3 x = glm::normalize(glm::cross(glm::dvec3(m[1]), z));
  const glm::dvec3 y = glm::cross(z, x);
  return glm::dmat4(glm::dvec4(x, 0.0), glm::dvec4(y, 0.0), glm::dvec4(z, 0.0), m[3]);
}

}  // namespace

CameraSpec viewThrough(Scene& scene, const std::string& which, int width, int height, glm::mat4* moved) {
  const FileCamera camera = pick(scene, which);
  const glm::dmat4 view = glm::inverse(rigid(camera.toWorld));
  const Bounds b = scene.bounds();
  const glm::dvec3 centre = glm::dvec3(view * glm::dvec4(glm::dvec3(b.center()), 1.0));
  const double distance = -centre.z;
  const double radius = 0.5 * glm::length(glm::dvec3(b.max - b.min));
  if (!(distance > 1e-6 * std::max(radius, 1e-30)))
    fail("--camera", "the scene's centre is not in front of camera '" + camera.name + "'");
  const glm::mat4 m(glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, distance)) * view);
  scene.transform(m);
  if (moved) *moved = m;
  const double aspect = double(width) / height;
  CameraSpec s;
  s.distance = distance;
  s.planeHeight = 2.0 * distance * std::tan(0.5 * camera.yfov);
  s.planeWidth = s.planeHeight * aspect;
  s.trackLeft = -0.25 * distance, s.trackRight = 0.25 * distance;
  s.rowTop = 0.25 * distance / aspect, s.rowBottom = -s.rowTop;
  s.nearDistance = std::max(distance - 1.5 * radius, 0.02 * distance);
  s.farDistance = distance + 1.5 * radius;
  scene.camera = s;
  return s;
}

}  // namespace mvr
