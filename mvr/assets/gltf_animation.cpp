// glTF animations as clips: node TRS and morph weight channels, their
// samplers checked against their times.
#include <cmath>

#include "mvr/error.h"
#include "mvr/assets/gltf_reader.h"

namespace mvr::gltf {

void GltfReader::readClips() {
  for (size_t i = 0; i < model_.animations.size(); ++i) {
    const tinygltf::Animation& g = model_.animations[i];
    AnimationClip clip;
    clip.name = g.name.empty() ? "animation " + std::to_string(i) : g.name;
    for (const tinygltf::AnimationChannel& c : g.channels) channel(g, c, clip);
    if (!clip.channels.empty()) animation_->clips.push_back(std::move(clip));
  }
  if (animation_->clips.empty()) return;
  scene_.animations.push_back(std::move(animation_));
}

void GltfReader::channel(const tinygltf::Animation& g, const tinygltf::AnimationChannel& c, AnimationClip& clip) {
  const auto path = c.target_path == "translation" ? AnimationChannel::Path::Translation
                    : c.target_path == "rotation"  ? AnimationChannel::Path::Rotation
                    : c.target_path == "scale"     ? AnimationChannel::Path::Scale
                    : c.target_path == "weights"   ? AnimationChannel::Path::Weights
                                                   : throw Error(path_ + ": animation channel of path '" +
                                                                 c.target_path.substr(0, 40) + "' is not glTF 2.0");
  if (c.sampler < 0 || size_t(c.sampler) >= g.samplers.size()) fail(path_, "animation sampler " + std::to_string(c.sampler) + " does not exist");
  const auto where = slots_.find(c.target_node);
  if (where == slots_.end()) return;  // a node outside the scene drawn
  const tinygltf::AnimationSampler& s = g.samplers[size_t(c.sampler)];
  AnimationChannel ch;
  ch.path = path;
  ch.interpolation = s.interpolation == "STEP"          ? AnimationChannel::Interpolation::Step
                     : s.interpolation == "CUBICSPLINE" ? AnimationChannel::Interpolation::CubicSpline
                                                        : AnimationChannel::Interpolation::Linear;
  const Accessor input(model_, s.input, path_), output(model_, s.output, path_);
  if (input.components() != 1) fail(path_, "animation input must be SCALAR times");
  const size_t perKey = ch.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 : 1;
  if (path == AnimationChannel::Path::Weights) {
    // SCALAR outputs, one per morph target and key part.
    const size_t keys = perKey * input.count();
    if (output.components() != 1 || keys == 0 || output.count() % keys || output.count() / keys > 4096)
      fail(path_, "animation output of weights does not match its times");
    ch.weights = int(output.count() / keys);
  }
  const size_t perValue = path == AnimationChannel::Path::Weights ? size_t(ch.weights) : 1;
  if (output.components() != (path == AnimationChannel::Path::Weights ? 1 : ch.components()))
    fail(path_, "animation output of " + c.target_path + " has the wrong type");
  if (input.count() == 0 || output.count() != perKey * perValue * input.count())
    fail(path_, "animation sampler has " + std::to_string(output.count()) + " values for " + std::to_string(input.count()) + " times");
  for (size_t k = 0; k < input.count(); ++k) {
    const float t = input.at(k).x;
    if (!std::isfinite(t) || (k > 0 && !(t > ch.times.back()))) fail(path_, "animation times must rise and be finite");
    ch.times.push_back(t);
  }
  for (size_t k = 0; k < output.count(); ++k) {
    const glm::vec4 v = output.at(k);
    for (int j = 0; j < output.components(); ++j) {
      if (!std::isfinite(v[j])) fail(path_, "animation values must be finite");
      ch.values.push_back(v[j]);
    }
  }
  for (int slot : where->second) {
    ch.node = slot;
    clip.channels.push_back(ch);
  }
}

}  // namespace mvr::gltf
