#include "mvr/scene_animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/scene.h"

namespace mvr {
namespace {

glm::vec4 at(const AnimationChannel& c, size_t key, int part) {
  const int n = c.components(), stride = c.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 * n : n;
  const float* v = c.values.data() + key * size_t(stride) + size_t(part * n);
  return n == 4 ? glm::vec4(v[0], v[1], v[2], v[3]) : glm::vec4(v[0], v[1], v[2], 0.0f);
}

glm::vec4 normalizedIfRotation(const AnimationChannel& c, glm::vec4 v) {
  if (c.path != AnimationChannel::Path::Rotation) return v;
  const float l = glm::length(v);
  return l > 0.0f ? v / l : glm::vec4(0, 0, 0, 1);
}

}  // namespace

glm::vec4 AnimationChannel::sample(double t) const {
  const bool cubic = interpolation == Interpolation::CubicSpline;
  const int valuePart = cubic ? 1 : 0;
  if (times.empty()) return glm::vec4(0.0f);
  if (t <= times.front()) return normalizedIfRotation(*this, at(*this, 0, valuePart));
  if (t >= times.back()) return normalizedIfRotation(*this, at(*this, times.size() - 1, valuePart));
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), float(t)) - times.begin()) - 1;
  const double t0 = times[k], dt = times[k + 1] - t0;
  const float s = dt > 0.0 ? float((t - t0) / dt) : 0.0f;
  switch (interpolation) {
    case Interpolation::Step:
      return normalizedIfRotation(*this, at(*this, k, 0));
    case Interpolation::Linear: {
      const glm::vec4 a = at(*this, k, 0), b = at(*this, k + 1, 0);
      if (path != Path::Rotation) return a + (b - a) * s;
      const glm::quat q = glm::slerp(glm::quat(a.w, a.x, a.y, a.z), glm::quat(b.w, b.x, b.y, b.z), s);
      return normalizedIfRotation(*this, glm::vec4(q.x, q.y, q.z, q.w));
    }
    case Interpolation::CubicSpline: {
      // Hermite: p(s) = (2s^3 - 3s^2 + 1) v0 + (s^3 - 2s^2 + s) dt b0 + (-2s^3 + 3s^2) v1 + (s^3 - s^2) dt a1,
      // b0 the out-tangent of key k, a1 the in-tangent of key k + 1.
      const float s2 = s * s, s3 = s2 * s, d = float(dt);
      const glm::vec4 v0 = at(*this, k, 1), b0 = at(*this, k, 2), a1 = at(*this, k + 1, 0), v1 = at(*this, k + 1, 1);
      return normalizedIfRotation(*this, (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * d * b0 +
                                             (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * d * a1);
    }
  }
  return glm::vec4(0.0f);
}

double AnimationClip::duration() const {
  double d = 0.0;
  for (const AnimationChannel& c : channels)
    if (!c.times.empty()) d = std::max(d, double(c.times.back()));
  return d;
}

double SceneAnimation::duration(int clip) const {
  if (clip >= 0) return clips[size_t(clip)].duration();
  double d = 0.0;
  for (const AnimationClip& c : clips) d = std::max(d, c.duration());
  return d;
}

int SceneAnimation::clipNamed(const std::string& name) const {
  for (size_t i = 0; i < clips.size(); ++i)
    if (clips[i].name == name) return int(i);
  return -1;
}

std::vector<glm::mat4> SceneAnimation::worldAt(double t, int clip) const {
  std::vector<glm::vec3> translation(nodes.size()), scale(nodes.size());
  std::vector<glm::quat> rotation(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i)
    translation[i] = nodes[i].translation, rotation[i] = nodes[i].rotation, scale[i] = nodes[i].scale;
  for (size_t c = 0; c < clips.size(); ++c) {
    if (clip != -1 && int(c) != clip) continue;  // -2: none plays
    for (const AnimationChannel& ch : clips[c].channels) {
      if (ch.node < 0 || size_t(ch.node) >= nodes.size()) continue;
      const glm::vec4 v = ch.sample(t);
      switch (ch.path) {
        case AnimationChannel::Path::Translation: translation[size_t(ch.node)] = glm::vec3(v); break;
        case AnimationChannel::Path::Rotation: rotation[size_t(ch.node)] = glm::quat(v.w, v.x, v.y, v.z); break;
        case AnimationChannel::Path::Scale: scale[size_t(ch.node)] = glm::vec3(v); break;
      }
    }
  }
  // Parents come before their children (the loader's order).
  std::vector<glm::mat4> world(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const AnimatedNode& n = nodes[i];
    const glm::mat4 local = n.hasMatrix ? n.matrix
                                        : glm::translate(glm::mat4(1.0f), translation[i]) * glm::mat4_cast(rotation[i]) *
                                              glm::scale(glm::mat4(1.0f), scale[i]);
    world[i] = (n.parent >= 0 ? world[size_t(n.parent)] : outer) * local;
  }
  return world;
}

void SceneAnimation::pose(Scene& scene, double t, int clip, const glm::mat4& after) const {
  const std::vector<glm::mat4> world = worldAt(t, clip);
  for (const AnimatedInstance& inst : instances) {
    if (inst.node < 0 || size_t(inst.node) >= world.size() || inst.first > scene.positions.size() ||
        inst.positions.size() > scene.positions.size() - inst.first)
      fail("animation", "a mesh instance outside the scene's vertices");
    const glm::mat4 m = after * world[size_t(inst.node)];
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
    for (size_t v = 0; v < inst.positions.size(); ++v) {
      scene.positions[inst.first + v] = glm::vec3(m * glm::vec4(inst.positions[v], 1.0f));
      const glm::vec3 n = normalMatrix * inst.normals[v];
      const float l = glm::length(n);
      scene.normals[inst.first + v] = l > 0.0f && std::isfinite(l) ? n / l : glm::vec3(0, 0, 1);
    }
  }
}

std::shared_ptr<SceneAnimation> SceneAnimation::offset(uint32_t vertexBase) const {
  auto a = std::make_shared<SceneAnimation>(*this);
  for (AnimatedInstance& inst : a->instances) inst.first += vertexBase;
  return a;
}

void poseAnimations(Scene& scene, double t, const std::string& clip, const glm::mat4& after) {
  for (const auto& a : scene.animations) {
    const int index = clip.empty() ? -1 : a->clipNamed(clip);
    if (!clip.empty() && index < 0) {
      a->pose(scene, 0.0, -2, after);  // no clip of this file plays: its rest pose
      continue;
    }
    a->pose(scene, t, index, after);
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
