#include "apps/cli/camera_flags.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/file_camera.h"

namespace mvr::app {
namespace {

double halfTan(double degrees) { return std::tan(0.5 * degrees * glm::pi<double>() / 180.0); }

std::vector<double> numbers(const std::string& text, const char* option) {
  std::vector<double> out;
  std::stringstream ss(text);
  for (std::string tok; std::getline(ss, tok, ',');) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (tok.empty() || *end != '\0' || !std::isfinite(v)) fail(option, "'" + text + "' is not R,G,B[,A]");
    out.push_back(v);
  }
  return out;
}

}  // namespace

std::string CameraFlags::firstGiven() const {
  for (const auto& [flag, given] : {std::pair{"--cone", cone.has_value()}, {"--fov", fov.has_value()},
                                    {"--focal", !focal.empty()}, {"--depthiness", depthiness.has_value()},
                                    {"--background", !background.empty()}, {"--opaque", opaque},
                                    {"--camera", !fileCamera.empty()}})
    if (given) return flag;
  return "";
}

void CameraFlags::add(CLI::App& app) {
  app.add_option("--cone", cone, "view cone in degrees: the track's angle seen from the image plane's centre")
      ->type_name("DEG");
  app.add_option("--fov", fov, "horizontal field of view of the centre view, degrees")->type_name("DEG");
  app.add_option("--focal", focal,
                 "the world z that sits on the display plane, or center (the scene's bounding-box centre)")
      ->type_name("Z|center");
  app.add_option("--depthiness", depthiness, "disparity scale: the track times S")->type_name("S");
  app.add_option("--background", background,
                 "composite over this linear colour, components 0..1 (alpha 1 if left out)")
      ->type_name("R,G,B[,A]");
  app.add_flag("--opaque", opaque, "alpha 1 everywhere (over --background, default black)");
  app.add_option("--camera", fileCamera,
                 "the scene file's camera (glTF), by name or index, as the centre view: its place, direction and "
                 "vertical field of view, the image plane through the scene's centre (default: framed on the scene)")
      ->type_name("NAME|INDEX");
}

void CameraFlags::validate() const {
  if (cone && !(*cone > 0.0 && *cone < 180.0)) fail("--cone", "expected degrees in (0, 180)");
  if (fov && !(*fov > 0.0 && *fov < 180.0)) fail("--fov", "expected degrees in (0, 180)");
  if (depthiness && !(*depthiness > 0.0 && std::isfinite(*depthiness))) fail("--depthiness", "expected a value > 0");
  if (!focal.empty() && focal != "center") {
    char* end = nullptr;
    const double z = std::strtod(focal.c_str(), &end);
    if (*end != '\0' || !std::isfinite(z)) fail("--focal", "'" + focal + "' is neither a number nor center");
  }
  backgroundColor();
}

glm::mat4 CameraFlags::viewThroughFileCamera(Scene& scene, int width, int height) const {
  glm::mat4 moved(1.0f);
  if (!fileCamera.empty()) viewThrough(scene, fileCamera, width, height, &moved);
  return moved;
}

double CameraFlags::placeFocalPlane(Scene& scene, const Bounds* framed) const {
  if (focal.empty()) return 0.0;
  const double z = focal == "center" ? double((framed ? *framed : scene.bounds()).center().z)
                                     : std::strtod(focal.c_str(), nullptr);
  // Its animations move with it: their poses come out behind the plane too.
  scene.transform(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -float(z))));
  return z;
}

CameraSpec CameraFlags::adjust(CameraSpec spec, int width, int height) const {
  const double aspect = double(width) / height;
  if (fov) {
    spec.planeWidth = 2.0 * spec.distance * halfTan(*fov);
    spec.planeHeight = 0.0;  // from the aspect
  }
  if (cone) {
    const double half = spec.distance * halfTan(*cone);
    spec.trackLeft = -half, spec.trackRight = half;
    spec.rowTop = half / aspect, spec.rowBottom = -half / aspect;
  }
  if (depthiness) {
    spec.trackLeft *= *depthiness, spec.trackRight *= *depthiness;
    spec.rowTop *= *depthiness, spec.rowBottom *= *depthiness;
  }
  return spec;
}

std::optional<glm::vec4> CameraFlags::backgroundColor() const {
  if (background.empty()) return opaque ? std::optional(glm::vec4(0, 0, 0, 1)) : std::nullopt;
  const std::vector<double> v = numbers(background, "--background");
  if (v.size() != 3 && v.size() != 4) fail("--background", "'" + background + "' is not R,G,B[,A]");
  for (double c : v)
    if (c < 0.0 || c > 1.0) fail("--background", "components must lie in 0..1");
  return glm::vec4(float(v[0]), float(v[1]), float(v[2]), opaque || v.size() == 3 ? 1.0f : float(v[3]));
}

}  // namespace mvr::app
