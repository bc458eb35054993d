#pragma once
// A scene file's animations (glTF's, issue 47): the node hierarchy with its
// rest transforms, the clips' channels, and each mesh instance's vertices
// in its node's space, so that the scene can be posed at any time t.
// Node TRS and morph weight channels with LINEAR (slerp for rotations),
// STEP and CUBICSPLINE interpolation (glTF 2.0, appendix C). A time before
// a channel's first key holds its first value, after its last key its
// last. A vertex is morphed first (base + sum of w_i * target_i, in its
// mesh's space), then skinned (sum of its up to four joints' weighted
// world * inverse bind matrices) or moved by its node's world transform.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

namespace mvr {

struct AnimationChannel {
  enum class Path { Translation, Rotation, Scale, Weights };
  enum class Interpolation { Linear, Step, CubicSpline };
  int node = 0;
  Path path = Path::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;   // ascending
  std::vector<float> values;  // per key components() floats; CUBICSPLINE: in-tangent, value, out-tangent
  int weights = 0;            // Path::Weights: the morph targets' count
  int components() const { return path == Path::Rotation ? 4 : path == Path::Weights ? weights : 3; }
  // The channel's value at time t into out[0, components()) (a rotation
  // as x, y, z, w, normalised).
  void sample(double t, float* out) const;
  glm::vec4 sample(double t) const;  // a TRS channel's
};

struct AnimationClip {
  std::string name;
  std::vector<AnimationChannel> channels;
  double duration() const;  // its last key's time
};

struct AnimatedNode {
  int parent = -1;
  bool hasMatrix = false;  // glTF: a node with a matrix is not animated
  glm::mat4 matrix{1.0f};
  glm::vec3 translation{0.0f}, scale{1.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  std::vector<float> weights;  // its mesh's morph weights at rest
};

// A glTF skin: its joints' places in the node list, and each joint's
// inverse bind matrix (mesh space to the joint's at bind time).
struct AnimatedSkin {
  std::vector<int> joints;
  std::vector<glm::mat4> inverseBind;
};

// A mesh drawn at a node: the scene's vertices [first, first + local
// positions' size) are these, moved by the node's world transform.
// Skinned (skin >= 0), its node's transform is not used (glTF's rule).
// flat: the vertices are triangles' corners, three by three, with the
// triangle's normal (a mesh without normals), recomputed when posed.
struct AnimatedInstance {
  int node = 0;
  uint32_t first = 0;
  bool flat = false;
  std::vector<glm::vec3> positions, normals;  // in the node's space
  // Morph targets: each one's displacements of every vertex (normals':
  // empty when the target has none).
  std::vector<std::vector<glm::vec3>> morphPositions, morphNormals;
  int skin = -1;
  // Per vertex jointSets influences of four (glTF's JOINTS_n, WEIGHTS_n
  // sets), their weights summing to 1 over all sets.
  int jointSets = 1;
  std::vector<glm::u16vec4> joints;  // into the skin's joints
  std::vector<glm::vec4> jointWeights;
};

// The nodes' world transforms (the scene file's transform included) and
// morph weights at one time.
struct NodePose {
  std::vector<glm::mat4> world;
  std::vector<std::vector<float>> weights;
};

struct SceneAnimation {
  std::vector<AnimatedNode> nodes;
  std::vector<AnimationClip> clips;
  std::vector<AnimatedInstance> instances;
  std::vector<AnimatedSkin> skins;
  glm::mat4 outer{1.0f};  // what moved the file's scene after loading (a scene file's transform)

  // The longest clip's, or the named one's (-1: every clip).
  double duration(int clip = -1) const;
  int clipNamed(const std::string& name) const;  // -1 when none
  // The nodes at time t with the clip (-1: every clip plays, -2: none).
  NodePose poseAt(double t, int clip) const;
  // The instances' vertices of a scene's positions and normals
  // (Scene::positions, ::normals) at time t, moved last by `after`.
  void pose(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, double t, int clip,
            const glm::mat4& after) const;
  // The same animation for a scene appended after `vertexBase` vertices.
  std::shared_ptr<SceneAnimation> offset(uint32_t vertexBase) const;
};

}  // namespace mvr
