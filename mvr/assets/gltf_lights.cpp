// KHR_lights_punctual: the file's lights placed by their nodes, and their
// physical units as our colours.
#include <algorithm>
#include <cmath>

#include "mvr/error.h"
#include "mvr/assets/gltf_reader.h"

namespace mvr::gltf {

void GltfReader::placeLight(const tinygltf::Value& ext, const glm::mat4& world) {
  const int index = ext.Has("light") && ext.Get("light").IsNumber() ? ext.Get("light").GetNumberAsInt() : -1;
  if (index < 0 || size_t(index) >= model_.lights.size()) fail(path_, "light " + std::to_string(index) + " does not exist");
  placedLights_.emplace_back(size_t(index), world);
}

// KHR_lights_punctual in its physical units as our colours, which are
// illuminance over pi (shading/brdf.h): a directional light of E lux is
// its colour times E / pi, a point or spot light of I candela its colour
// times I / pi at distance 1, falling off as 1/d^2 within its range. The
// brightest at the centre of the scene's bounds are kept, and what brings
// their illuminance there to a sum of 1 is each one's autoExposure.
void GltfReader::addLights() {
  const glm::vec3 centre = scene_.bounds().center();
  std::vector<std::pair<double, Light>> lit;  // illuminance at the centre, light
  for (const auto& [index, world] : placedLights_) {
    const tinygltf::Light& g = model_.lights[index];
    Light light;
    if (g.color.size() == 3)
      light.color = glm::clamp(glm::vec3(float(g.color[0]), float(g.color[1]), float(g.color[2])), 0.0f, 1.0f);
    const double intensity = std::isfinite(g.intensity) ? std::clamp(g.intensity, 0.0, 1e30) : 0.0;
    light.color *= float(intensity / M_PI);
    // Directional and spot lights shine down their node's -z.
    const glm::vec3 minusZ = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
    const glm::vec3 down = glm::length(minusZ) > 0.0f ? glm::normalize(minusZ) : glm::vec3(0.0f, 0.0f, -1.0f);
    if (g.type == "directional") {
      light.vector = down;
    } else {
      light.type = g.type == "spot" ? Light::Type::Spot : Light::Type::Point;
      light.vector = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      light.falloff = true;
      light.range = std::isfinite(g.range) && g.range > 0.0 ? float(std::min(g.range, 1e30)) : 0.0f;
      if (light.type == Light::Type::Spot) {
        light.axis = down;
        const double outer = std::clamp(g.spot.outerConeAngle, 0.0, M_PI / 2);
        light.cosOuter = float(std::cos(outer));
        light.cosInner = float(std::cos(std::clamp(g.spot.innerConeAngle, 0.0, outer)));
      }
    }
    // A spot's as if the centre were on its axis: it is aimed at what it lights.
    const double illuminance = intensity * distanceFalloff(light, centre);
    if (illuminance > 0.0 && std::isfinite(illuminance)) lit.emplace_back(illuminance, light);
  }
  if (lit.empty()) {
    if (!placedLights_.empty()) warn_("its lights have no intensity: the default light is used");
    return;
  }
  std::stable_sort(lit.begin(), lit.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (lit.size() > size_t(kMaxLights)) {
    warn_(std::to_string(lit.size()) + " lights: the " + std::to_string(kMaxLights) + " brightest are used");
    lit.resize(size_t(kMaxLights));
  }
  double sum = 0.0;
  for (const auto& l : lit) sum += l.first;
  const float exposure = float(std::min(M_PI / sum, 1e30));
  for (auto& [illuminance, light] : lit) {
    light.autoExposure = exposure;
    scene_.lights.push_back(light);
  }
}

}  // namespace mvr::gltf
