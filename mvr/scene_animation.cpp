#include "mvr/scene_animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {
namespace {

// Key `key`'s part (CUBICSPLINE: 0 in-tangent, 1 value, 2 out-tangent).
const float* at(const AnimationChannel& c, size_t key, int part) {
  const int n = c.components(), stride = c.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 * n : n;
  return c.values.data() + key * size_t(stride) + size_t(part * n);
}

void copy(const float* v, int n, float* out) { std::copy(v, v + n, out); }

void normalizeIfRotation(const AnimationChannel& c, float* v) {
  if (c.path != AnimationChannel::Path::Rotation) return;
  const float l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
  if (l > 0.0f)
    for (int i = 0; i < 4; ++i) v[i] /= l;
  else
    v[0] = v[1] = v[2] = 0.0f, v[3] = 1.0f;
}

}  // namespace

void AnimationChannel::sample(double t, float* out) const {
  const int n = components();
  const bool cubic = interpolation == Interpolation::CubicSpline;
  const int valuePart = cubic ? 1 : 0;
  if (times.empty()) return std::fill(out, out + n, 0.0f);
  if (t <= times.front() || t >= times.back()) {
    copy(at(*this, t <= times.front() ? 0 : times.size() - 1, valuePart), n, out);
    return normalizeIfRotation(*this, out);
  }
  const size_t k = size_t(std::upper_bound(times.begin(), times.end(), float(t)) - times.begin()) - 1;
  const double t0 = times[k], dt = times[k + 1] - t0;
  const float s = dt > 0.0 ? float((t - t0) / dt) : 0.0f;
  switch (interpolation) {
    case Interpolation::Step:
      copy(at(*this, k, 0), n, out);
      break;
    case Interpolation::Linear: {
      const float *a = at(*this, k, 0), *b = at(*this, k + 1, 0);
      if (path == Path::Rotation) {
        const glm::quat q = glm::slerp(glm::quat(a[3], a[0], a[1], a[2]), glm::quat(b[3], b[0], b[1], b[2]), s);
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
      } else {
        for (int i = 0; i < n; ++i) out[i] = a[i] + (b[i] - a[i]) * s;
      }
      break;
    }
    case Interpolation::CubicSpline: {
      // Hermite: p(s) = (2s^3 - 3s^2 + 1) v0 + (s^3 - 2s^2 + s) dt b0 + (-2s^3 + 3s^2) v1 + (s^3 - s^2) dt a1,
      // b0 the out-tangent of key k, a1 the in-tangent of key k + 1.
      const float s2 = s * s, s3 = s2 * s, d = float(dt);
      const float *v0 = at(*this, k, 1), *b0 = at(*this, k, 2), *a1 = at(*this, k + 1, 0), *v1 = at(*this, k + 1, 1);
      for (int i = 0; i < n; ++i)
        out[i] = (2 * s3 - 3 * s2 + 1) * v0[i] + (s3 - 2 * s2 + s) * d * b0[i] + (-2 * s3 + 3 * s2) * v1[i] +
                 (s3 - s2) * d * a1[i];
      break;
    }
  }
  normalizeIfRotation(*this, out);
}

glm::vec4 AnimationChannel::sample(double t) const {
  glm::vec4 v(0.0f);
  if (components() <= 4) sample(t, &v[0]);
  return v;
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

NodePose SceneAnimation::poseAt(double t, int clip) const {
  NodePose pose;
  std::vector<glm::vec3> translation(nodes.size()), scale(nodes.size());
  std::vector<glm::quat> rotation(nodes.size());
  pose.weights.resize(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    translation[i] = nodes[i].translation, rotation[i] = nodes[i].rotation, scale[i] = nodes[i].scale;
    pose.weights[i] = nodes[i].weights;
  }
  for (size_t c = 0; c < clips.size(); ++c) {
    if (clip != -1 && int(c) != clip) continue;  // -2: none plays
    for (const AnimationChannel& ch : clips[c].channels) {
      if (ch.node < 0 || size_t(ch.node) >= nodes.size()) continue;
      const size_t node = size_t(ch.node);
      if (ch.path == AnimationChannel::Path::Weights) {
        pose.weights[node].resize(size_t(ch.weights));
        ch.sample(t, pose.weights[node].data());
        continue;
      }
      const glm::vec4 v = ch.sample(t);
      switch (ch.path) {
        case AnimationChannel::Path::Translation: translation[node] = glm::vec3(v); break;
        case AnimationChannel::Path::Rotation: rotation[node] = glm::quat(v.w, v.x, v.y, v.z); break;
        case AnimationChannel::Path::Scale: scale[node] = glm::vec3(v); break;
        case AnimationChannel::Path::Weights: break;
      }
    }
  }
  // Parents come before their children (the loader's order).
  pose.world.resize(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const AnimatedNode& n = nodes[i];
    const glm::mat4 local = n.hasMatrix ? n.matrix
                                        : glm::translate(glm::mat4(1.0f), translation[i]) * glm::mat4_cast(rotation[i]) *
                                              glm::scale(glm::mat4(1.0f), scale[i]);
    pose.world[i] = (n.parent >= 0 ? pose.world[size_t(n.parent)] : outer) * local;
  }
  return pose;
}

namespace {

glm::vec3 unitOr(glm::vec3 v, glm::vec3 fallback) {
  const float l = glm::length(v);
  return l > 0.0f && std::isfinite(l) ? v / l : fallback;
}

// An instance's vertex v morphed by `weights`, in its mesh's space.
void morphed(const AnimatedInstance& inst, const std::vector<float>& weights, size_t v, glm::vec3& p, glm::vec3& n) {
  p = inst.positions[v], n = inst.normals[v];
  const size_t targets = std::min(weights.size(), inst.morphPositions.size());
  for (size_t i = 0; i < targets; ++i) {
    if (weights[i] == 0.0f) continue;
    p += weights[i] * inst.morphPositions[i][v];
    if (!inst.morphNormals[i].empty()) n += weights[i] * inst.morphNormals[i][v];
  }
}

// One instance posed into the scene's vertices: each vertex's matrix is
// its node's (rigid) or its joints' blend (skinned), then `after`.
void poseInstance(const AnimatedInstance& inst, const NodePose& pose, const std::vector<glm::mat4>& joints,
                  const glm::mat4& after, std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
  const glm::mat4 rigid = after * pose.world[size_t(inst.node)];
  const glm::mat3 rigidNormals = glm::transpose(glm::inverse(glm::mat3(rigid)));
  const std::vector<float>& weights = pose.weights[size_t(inst.node)];
  const bool skinned = inst.skin >= 0;
  const size_t sets = size_t(std::max(inst.jointSets, 1));
  constexpr int kBlock = 4096;
  const int blocks = int((inst.positions.size() + kBlock - 1) / kBlock);
  auto run = [&](int b) {
    const size_t end = std::min(inst.positions.size(), size_t(b + 1) * kBlock);
    for (size_t v = size_t(b) * kBlock; v < end; ++v) {
      glm::vec3 p, n;
      morphed(inst, weights, v, p, n);
      glm::mat4 m = rigid;
      if (skinned) {
        glm::mat4 blend(0.0f);
        for (size_t s = v * sets; s < (v + 1) * sets; ++s) {
          const glm::u16vec4 j = inst.joints[s];
          const glm::vec4 w = inst.jointWeights[s];
          blend += w.x * joints[j.x] + w.y * joints[j.y] + w.z * joints[j.z] + w.w * joints[j.w];
        }
        m = after * blend;
      }
      positions[inst.first + v] = glm::vec3(m * glm::vec4(p, 1.0f));
      if (inst.flat) continue;  // its normals come from the posed triangles, below
      const glm::mat3 normalMatrix = skinned ? glm::transpose(glm::inverse(glm::mat3(m))) : rigidNormals;
      normals[inst.first + v] = unitOr(normalMatrix * n, glm::vec3(0, 0, 1));
    }
  };
  if (blocks > 1 && (skinned || !inst.morphPositions.empty()))
    parallelFor(0, blocks, run);
  else
    for (int b = 0; b < blocks; ++b) run(b);
  if (!inst.flat) return;
  // A triangle's own normal, from its posed corners (the loader's winding).
  for (size_t v = 0; v + 2 < inst.positions.size(); v += 3) {
    const glm::vec3 a = positions[inst.first + v], b = positions[inst.first + v + 1],
                    c = positions[inst.first + v + 2];
    const glm::vec3 n = unitOr(glm::cross(b - a, c - a), glm::vec3(0, 0, 1));
    for (size_t k = 0; k < 3; ++k) normals[inst.first + v + k] = n;
  }
}

}  // namespace

void SceneAnimation::pose(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, double t, int clip,
                          const glm::mat4& after) const {
  const NodePose nodePose = poseAt(t, clip);
  // Each skin's joint matrices: the joint's world transform times its inverse bind matrix.
  std::vector<std::vector<glm::mat4>> skinJoints(skins.size());
  for (size_t s = 0; s < skins.size(); ++s)
    for (size_t j = 0; j < skins[s].joints.size(); ++j)
      skinJoints[s].push_back(nodePose.world[size_t(skins[s].joints[j])] * skins[s].inverseBind[j]);
  static const std::vector<glm::mat4> none;
  for (const AnimatedInstance& inst : instances) {
    if (inst.node < 0 || size_t(inst.node) >= nodes.size() || inst.first > positions.size() ||
        inst.positions.size() > positions.size() - inst.first || normals.size() != positions.size() || inst.skin >= int(skins.size()) ||
        (inst.skin >= 0 && (inst.joints.size() != inst.positions.size() * size_t(std::max(inst.jointSets, 1)) ||
                            inst.jointWeights.size() != inst.joints.size())))
      fail("animation", "a mesh instance outside the scene's vertices");
    poseInstance(inst, nodePose, inst.skin >= 0 ? skinJoints[size_t(inst.skin)] : none, after, positions, normals);
  }
}

std::shared_ptr<SceneAnimation> SceneAnimation::offset(uint32_t vertexBase) const {
  auto a = std::make_shared<SceneAnimation>(*this);
  for (AnimatedInstance& inst : a->instances) inst.first += vertexBase;
  return a;
}

}  // namespace mvr
