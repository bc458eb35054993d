// glTF skins and morph targets: the animated node list, each skin's joints
// and inverse bind matrices, and each primitive's per-vertex deformation.
#include <cmath>

#include "mvr/error.h"
#include "mvr/assets/gltf_reader.h"

namespace mvr::gltf {

// The node in the animation's list (parents before children), with its
// rest transform; slots_ maps the file's node to its places.
int GltfReader::animatedNode(int index, int parentSlot) {
  const tinygltf::Node& n = model_.nodes[size_t(index)];
  AnimatedNode a;
  a.parent = parentSlot;
  if (n.matrix.size() == 16) {
    a.hasMatrix = true;
    a.matrix = localTransform(n);
  } else {
    if (n.translation.size() == 3) a.translation = glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
    if (n.rotation.size() == 4)
      a.rotation = glm::normalize(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
    if (n.scale.size() == 3) a.scale = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
  }
  // Morph weights: the node's, else its mesh's.
  const std::vector<double>* w = &n.weights;
  if (w->empty() && n.mesh >= 0 && size_t(n.mesh) < model_.meshes.size()) w = &model_.meshes[size_t(n.mesh)].weights;
  for (double x : *w) a.weights.push_back(std::isfinite(x) ? float(x) : 0.0f);
  const int slot = int(animation_->nodes.size());
  animation_->nodes.push_back(a);
  slots_[index].push_back(slot);
  return slot;
}

// The skins the instances use, with their joints' places in the node
// list. A joint outside the scene drawn cannot move: its skin's meshes
// are drawn rigid, as their nodes place them.
void GltfReader::readSkins() {
  std::map<int, int> ours;  // the file's skin, ours (-1: not usable)
  for (AnimatedInstance& inst : animation_->instances) {
    if (inst.skin < 0) continue;
    if (size_t(inst.skin) >= model_.skins.size()) fail(path_, "skin " + std::to_string(inst.skin) + " does not exist");
    if (inst.joints.empty()) {
      inst.skin = -1;  // a primitive without JOINTS_0
      continue;
    }
    auto [it, added] = ours.emplace(inst.skin, -1);
    if (added) it->second = skin(size_t(inst.skin));
    inst.skin = it->second;
  }
}

int GltfReader::skin(size_t index) {
  const tinygltf::Skin& g = model_.skins[index];
  AnimatedSkin s;
  std::unique_ptr<Accessor> inverse;
  if (g.inverseBindMatrices >= 0) {
    inverse = std::make_unique<Accessor>(model_, g.inverseBindMatrices, path_);
    if (inverse->count() < g.joints.size()) fail(path_, "skin " + std::to_string(index) + " has fewer inverse bind matrices than joints");
  }
  for (size_t j = 0; j < g.joints.size(); ++j) {
    const auto where = slots_.find(g.joints[j]);
    if (where == slots_.end()) {
      warn_("a skin's joint is not in the scene drawn: its meshes drawn unskinned");
      return -1;
    }
    s.joints.push_back(where->second.front());
    s.inverseBind.push_back(inverse ? inverse->matrix(j) : glm::mat4(1.0f));
  }
  animation_->skins.push_back(std::move(s));
  return int(animation_->skins.size()) - 1;
}

// Every set's influences of vertex k, their weights normalised together
// (they should sum to 1, the spec says; exporters round). A vertex
// without any weight follows its first joint.
void GltfReader::Deformation::add(uint32_t k, AnimatedInstance& inst) const {
  for (size_t i = 0; i < positions.size(); ++i) {
    inst.morphPositions[i].push_back(positions[i] ? glm::vec3(positions[i]->at(k)) : glm::vec3(0.0f));
    if (normals[i]) inst.morphNormals[i].push_back(glm::vec3(normals[i]->at(k)));
  }
  if (joints.empty()) return;
  float sum = 0.0f;
  const size_t first = inst.jointWeights.size();
  for (size_t s = 0; s < joints.size(); ++s) {
    const glm::uvec4 j(joints[s]->at(k));
    const glm::vec4 w = glm::max(weights[s]->at(k), glm::vec4(0.0f));
    for (int c = 0; c < 4; ++c)
      if (w[c] > 0.0f && j[c] >= jointCount)
        throw Error(path + ": JOINTS_" + std::to_string(s) + " names joint " + std::to_string(j[c]) + " of a skin of " +
                    std::to_string(jointCount));
    sum += w.x + w.y + w.z + w.w;
    inst.joints.push_back(glm::u16vec4(glm::min(j, glm::uvec4(uint32_t(std::max<size_t>(jointCount, 1) - 1)))));
    inst.jointWeights.push_back(w);
  }
  const bool usable = sum > 0.0f && std::isfinite(sum);
  for (size_t s = first; s < inst.jointWeights.size(); ++s)
    inst.jointWeights[s] = usable ? inst.jointWeights[s] / sum : glm::vec4(s == first ? 1.0f : 0.0f, 0, 0, 0);
}

GltfReader::Deformation GltfReader::deformation(const tinygltf::Primitive& p, size_t count, bool hasNormals) {
  Deformation d;
  d.path = path_;
  if (!instance_) return d;
  for (const auto& target : p.targets) {
    auto accessor = [&](const char* name) -> std::shared_ptr<const Accessor> {
      const auto it = target.find(name);
      if (it == target.end()) return nullptr;
      auto a = std::make_shared<const Accessor>(model_, it->second, path_);
      if (a->components() != 3 || a->count() != count) fail(path_, std::string("a morph target's ") + name + " must be VEC3, one per vertex");
      return a;
    };
    d.positions.push_back(accessor("POSITION"));
    d.normals.push_back(hasNormals ? accessor("NORMAL") : nullptr);
  }
  instance_->morphPositions.resize(d.positions.size());
  instance_->morphNormals.resize(d.positions.size());
  const int skin = model_.nodes[size_t(currentNode_)].skin;
  if (skin < 0 || size_t(skin) >= model_.skins.size()) return d;
  for (int s = 0; p.attributes.count("JOINTS_" + std::to_string(s)); ++s) {
    const std::string joints = "JOINTS_" + std::to_string(s), weights = "WEIGHTS_" + std::to_string(s);
    if (!p.attributes.count(weights)) fail(path_, joints + " without " + weights);
    d.joints.push_back(attribute(p, joints));
    d.weights.push_back(attribute(p, weights));
    if (d.joints.back()->components() != 4 || d.weights.back()->components() != 4 || d.joints.back()->count() != count ||
        d.weights.back()->count() != count)
      fail(path_, joints + " and " + weights + " must be VEC4, one per vertex");
  }
  instance_->jointSets = int(d.joints.size());
  d.jointCount = model_.skins[size_t(skin)].joints.size();
  return d;
}

}  // namespace mvr::gltf
