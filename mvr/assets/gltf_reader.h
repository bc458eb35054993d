#pragma once
// The glTF reader's state while it walks one file (internal to mvr/io):
// the walk of scenes, nodes and primitives (gltf_reader.cpp), materials
// (gltf_materials.cpp), lights (gltf_lights.cpp), skins and morph targets
// (gltf_skins.cpp) and clips (gltf_animation.cpp).
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "mvr/assets/gltf_accessor.h"
#include "mvr/assets/gltf_draco.h"
#include "mvr/assets/load_warnings.h"
#include "mvr/assets/point_line_solids.h"
#include "mvr/scene.h"
#include "mvr/scene_animation.h"

namespace mvr::gltf {

// A number of an extension's object (index >= 0: of its array), else fallback.
double numberOr(const tinygltf::Value& object, const char* key, int index, double fallback);

// A node's transform in its parent's space (its matrix, or T R S).
glm::mat4 localTransform(const tinygltf::Node& n);

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}
  Scene read();

 private:
  std::string whyNoTriangles() const;
  // What moves a primitive's vertices besides its node: morph targets'
  // displacements and skin joints, read once and added per vertex.
  struct Deformation {
    std::string path;
    std::vector<std::shared_ptr<const Accessor>> positions, normals;  // per target; null: none
    std::vector<std::shared_ptr<const Accessor>> joints, weights;     // per JOINTS_n / WEIGHTS_n set
    size_t jointCount = 0;
    void add(uint32_t k, AnimatedInstance& inst) const;
  };

  // Walk (gltf_reader.cpp).
  std::vector<int> roots() const;
  void node(int index, const glm::mat4& parent, int parentSlot);
  void primitive(const tinygltf::Primitive& p, const glm::mat4& world);
  void pointsAndLines(const tinygltf::Primitive& p, const glm::mat4& world);
  std::vector<glm::uvec3> corners(const tinygltf::Primitive& p, size_t vertices);
  // The primitive's attribute (null: none) and indices (null: none), from
  // its Draco data where it is compressed.
  std::shared_ptr<const Accessor> attribute(const tinygltf::Primitive& p, const std::string& name);
  std::shared_ptr<const Accessor> indices(const tinygltf::Primitive& p);
  void camera(const tinygltf::Node& n, const glm::mat4& world);
  void reserve(size_t vertices, size_t triangles);
  void add(glm::uvec3 t, bool mirrored, uint32_t materialId);
  uint32_t defaultMaterial();
  void warnUnread();

  // Materials (gltf_materials.cpp).
  void readMaterials();
  Material material(size_t i);
  void metallicRoughness(const tinygltf::Material& g, Material& m);
  void mask(const tinygltf::Material& g, Material& m);
  int textureSource(const tinygltf::TextureInfo& t);
  void emission(const tinygltf::Material& g, size_t material, Material& m);
  void unlit(const tinygltf::Material& g, Material& m);

  // Lights (gltf_lights.cpp).
  void placeLight(const tinygltf::Value& ext, const glm::mat4& world);
  void addLights();

  // Skins and morph targets (gltf_skins.cpp).
  int animatedNode(int index, int parentSlot);
  void readSkins();
  int skin(size_t index);
  Deformation deformation(const tinygltf::Primitive& p, size_t count, bool hasNormals);

  // Clips (gltf_animation.cpp).
  void readClips();
  void channel(const tinygltf::Animation& g, const tinygltf::AnimationChannel& c, AnimationClip& clip);

  const tinygltf::Model& model_;
  std::string path_;
  Scene scene_;
  std::vector<bool> onPath_;
  std::unique_ptr<DracoPrimitive> draco_;  // the primitive being read, decoded, where compressed
  PointLineSet marks_;  // the points and lines, drawn as solids after the triangles
  std::vector<std::pair<size_t, glm::mat4>> placedLights_;  // light, its node's world transform
  std::vector<glm::mat3> uvTransforms_;  // per material: its base colour texture's KHR_texture_transform
  std::vector<int> uvSets_;              // per material: the TEXCOORD_n its base colour texture reads
  std::vector<bool> hidden_;             // per material: masked out whole (alphaMode MASK, no texture)
  std::shared_ptr<SceneAnimation> animation_;  // when the file has animations
  AnimatedInstance* instance_ = nullptr;       // the primitive being read, when animated
  int currentNode_ = -1;                       // the node whose mesh is being read
  std::map<int, std::vector<int>> slots_;      // a file node's places in animation_->nodes
  LoadWarnings warn_{scene_, path_};
  bool anyUv_ = false;
  int defaultMaterial_ = -1;
};

}  // namespace mvr::gltf
