#include "slicing/highlight_splits.h"

#include <algorithm>
#include <cmath>

#include "shading/brdf.h"
#include "shading/lighting.h"
#include "shading/view_dependent.h"

namespace mvr {

std::optional<double> closestTrackX(const glm::dvec3& p, const glm::dvec3& dir, double trackY,
                                    double trackZ, double* rayDistance) {
  // Lines p + t dir and (s, trackY, trackZ): minimise |p + t dir - q(s)|.
  const glm::dvec3 w0 = p - glm::dvec3(0.0, trackY, trackZ);
  const double b = dir.x, denom = 1.0 - b * b;
  if (denom < 1e-9) return std::nullopt;
  const double t = (b * w0.x - glm::dot(dir, w0)) / denom;
  if (t <= 0.0) return std::nullopt;
  if (rayDistance) *rayDistance = t;
  return w0.x + b * t;  // s = (e.w0 - b (d.w0)) / denom, rewritten with t
}

HighlightSplitter::HighlightSplitter(const Scene& scene, const ShearingCamera& cam, int row, int splits)
    : scene_(scene), cam_(cam), row_(row), splits_(splits) {}

bool HighlightSplitter::specular(uint32_t material) const {
  return material < scene_.materials.size() && scene_.materials[material].specular != glm::vec3(0.0f);
}

int HighlightSplitter::add(const glm::vec3& p, const glm::vec3& n, uint32_t material,
                           std::vector<HighlightKnot>& out) const {
  if (!specular(material)) return 0;
  const Material& m = scene_.materials[material];
  const int views = cam_.views();
  std::vector<float> rows = {0.0f, float(views)};
  if (views > 1 && splits_ > 0) {
    // The view direction's angle off the mirror ray where the highlight
    // has fallen to fraction f: cos^s = f (Blinn-Phong's half vector turns
    // half as fast as the view; GGX's lobe is taken as the Blinn-Phong one
    // of its width).
    const bool ggx = m.specularModel == SpecularModel::Ggx;
    const float turn = m.specularModel == SpecularModel::Phong ? 1.0f : 2.0f;
    const float exponent = ggx ? shading::ggxBlinnExponent(m.roughness) : m.shininess;
    auto angleAt = [&](float f) {
      return std::min(1.4f, turn * std::acos(std::pow(f, 1.0f / std::max(exponent, 1e-3f))));
    };
    const glm::dvec3 track = cam_.eye(0.0, row_);  // the track line: y and z of every eye
    for (const Light& light : scene_.lights) {
      const glm::vec3 l = shading::towardsLight(light, p);
      if (glm::dot(n, l) <= 0.0f) continue;
      double distance = 0.0;
      const auto peak = closestTrackX(p, glm::reflect(-l, n), track.y, track.z, &distance);
      if (!peak) continue;
      std::vector<double> xs = {*peak};
      for (int k = 1; k <= splits_; ++k) {  // equal steps of intensity down the lobe
        const double off = distance * std::tan(angleAt(1.0f - float(k) / float(splits_ + 1)));
        xs.push_back(*peak - off);
        xs.push_back(*peak + off);
      }
      for (double x : xs) {
        const float r = rowOf(x);
        if (r > 0.0f && r < float(views)) rows.push_back(r);
      }
    }
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end(), [](float a, float b) { return b - a < 1e-3f; }),
               rows.end());
  }
  for (float r : rows) out.push_back({r, shading::specularLight(scene_, m, p, n, eyeAt(r))});
  return int(rows.size());
}

}  // namespace mvr
