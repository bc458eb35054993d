#include "mvr/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mvr/scene_animation.h"

namespace mvr {

void Material::setMetallicRoughness(const glm::vec3& base, float metallic, float roughness,
                                    const glm::vec3& dielectricF0, float dielectricF90) {
  const glm::vec3 b = glm::clamp(base, 0.0f, 1.0f);
  const float m = std::clamp(metallic, 0.0f, 1.0f);
  specularModel = SpecularModel::Ggx;
  diffuse = b * (1.0f - m);
  this->dielectricF0 = glm::clamp(dielectricF0, 0.0f, 1.0f);
  specular = glm::mix(this->dielectricF0, b, m);
  specularF90 = glm::mix(std::clamp(dielectricF90, 0.0f, 1.0f), 1.0f, m);
  this->roughness = std::clamp(roughness, 0.0f, 1.0f);
}

std::vector<uint32_t> Scene::vertexMaterials() const {
  std::vector<uint32_t> m(vertexCount(), 0);
  for (size_t t = 0; t < triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) m[triangles[t][k]] = materialIds[t];
  return m;
}

Bounds Scene::bounds() const {
  if (positions.empty()) return {};
  Bounds b = Bounds::none();
  for (const glm::vec3& p : positions) b.include(p);
  return b;
}

void Scene::append(const Scene& other) {
  const auto base = uint32_t(positions.size());
  const auto materialBase = uint32_t(materials.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  colors.insert(colors.end(), other.colors.begin(), other.colors.end());
  // uvs stay either empty or one per vertex.
  if (!other.uvs.empty() || !uvs.empty()) {
    uvs.resize(base, glm::vec2(0.0f));
    if (other.uvs.empty())
      uvs.resize(positions.size(), glm::vec2(0.0f));
    else
      uvs.insert(uvs.end(), other.uvs.begin(), other.uvs.end());
  }
  for (const glm::uvec3& t : other.triangles) triangles.push_back(t + glm::uvec3(base));
  for (uint32_t m : other.materialIds) materialIds.push_back(m + materialBase);
  materials.insert(materials.end(), other.materials.begin(), other.materials.end());
  droppedFaces += other.droppedFaces;
  warnings.insert(warnings.end(), other.warnings.begin(), other.warnings.end());
  fileCameras.insert(fileCameras.end(), other.fileCameras.begin(), other.fileCameras.end());
  for (const auto& a : other.animations) animations.push_back(a->offset(uint32_t(base)));
}

void Scene::transformGeometry(const glm::mat4& m) {
  // A translation leaves directions as they are, to the bit.
  const bool turns = glm::mat3(m) != glm::mat3(1.0f);
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(glm::mat3(m))));
  for (glm::vec3& p : positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
  for (glm::vec3& n : normals)
    if (turns) n = glm::vec3(glm::normalize(normalMatrix * glm::dvec3(n)));
}

void Environment::turn(float degrees) {
  const float a = glm::radians(degrees), c = std::cos(a), s = std::sin(a);
  const glm::mat3 back(glm::vec3(c, 0.0f, s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-s, 0.0f, c));
  fromScene = back * fromScene;
}

void Scene::transform(const glm::mat4& m) {
  transformGeometry(m);
  fromFile = m * fromFile;
  const bool turns = glm::mat3(m) != glm::mat3(1.0f);
  const auto turn = [&](glm::vec3& d) { d = glm::vec3(glm::normalize(glm::dmat3(glm::mat3(m)) * glm::dvec3(d))); };
  for (Light& light : lights) {
    if (light.positional())
      light.vector = glm::vec3(m * glm::vec4(light.vector, 1.0f));
    else if (turns)
      turn(light.vector);
    if (light.type == Light::Type::Spot && turns) turn(light.axis);
    if (light.falloff && turns) {
      // Scaled by s, distances grow by s: the range follows, and the
      // colour at distance 1 by s^2, so the light reaches what it lit.
      const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(glm::mat3(m)))));
      light.range = float(light.range * scale);
      light.color = glm::vec3(glm::dvec3(light.color) * (scale * scale));
    }
  }
  if (environment && turns) {
    // Directions turn by m's rotation (a similarity: its columns scaled
    // alike); the map stays where it was, so lookups turn back.
    glm::mat3 r = glm::mat3(glm::dmat3(glm::mat3(m)));
    for (int c = 0; c < 3; ++c) r[c] = glm::normalize(r[c]);
    environment->fromScene = environment->fromScene * glm::transpose(r);
  }
  for (FileCamera& c : fileCameras) c.toWorld = m * c.toWorld;
  for (auto& a : animations) {
    auto moved = std::make_shared<SceneAnimation>(*a);
    moved->outer = m * moved->outer;
    a = std::move(moved);
  }
}

}  // namespace mvr

namespace mvr {

glm::vec2 coneScaleOffset(const Light& light) {
  if (light.type != Light::Type::Spot) return {0.0f, 1.0f};
  // A cone with no falloff band (inner = outer) would divide by zero: a
  // thousandth of a cosine is a band too narrow to see.
  const float scale = 1.0f / std::max(light.cosInner - light.cosOuter, 1e-3f);
  return {scale, -light.cosOuter * scale};
}

float distanceFalloff(const Light& light, const glm::vec3& p) {
  if (!light.falloff) return 1.0f;
  const float d2 = std::max(glm::dot(light.vector - p, light.vector - p), 0.01f);
  if (!(light.range > 0.0f)) return 1.0f / d2;
  const float q = d2 / (light.range * light.range);
  return std::clamp(1.0f - q * q, 0.0f, 1.0f) / d2;
}

glm::vec3 incidentLight(const Light& light, const glm::vec3& p, const glm::vec3& l) {
  return light.color * (coneFactor(light, l) * distanceFalloff(light, p));
}

float coneFactor(const Light& light, const glm::vec3& l) {
  const glm::vec2 c = coneScaleOffset(light);
  const float t = glm::clamp(glm::dot(light.axis, -l) * c.x + c.y, 0.0f, 1.0f);
  return t * t;
}

void computeVertexNormals(Scene& scene) {
  // In double: the cross product of float coordinates of 1e10 has a squared
  // length beyond float's range, and the normal would come out zero.
  std::vector<glm::dvec3> sum(scene.vertexCount(), glm::dvec3(0.0));
  for (const glm::uvec3& t : scene.triangles) {
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // length = twice the area
    for (int k = 0; k < 3; ++k) sum[t[k]] += n;
  }
  scene.normals.resize(scene.vertexCount());
  for (size_t v = 0; v < sum.size(); ++v) {
    const double len = glm::length(sum[v]);
    scene.normals[v] = len > 0 ? glm::vec3(sum[v] / len) : glm::vec3(0, 0, 1);
  }
}

}  // namespace mvr
