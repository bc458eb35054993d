// The walk of a glTF file: its scene's nodes down the hierarchy, each
// mesh's primitives as our triangles at the node's world transform.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "mvr/error.h"
#include "mvr/assets/gltf_reader.h"
#include "mvr/assets/mesh_check.h"
#include "mvr/assets/point_line_solids.h"

namespace mvr::gltf {
namespace {

// Triangles one file may expand to (instancing can multiply a small file).
constexpr size_t kMaxTriangles = size_t(1) << 28;

// Extensions read where they are used; any other is named in a warning.
bool isRead(const std::string& e) {
  return e == "KHR_texture_transform" || e == "KHR_lights_punctual" || e == "KHR_mesh_quantization" ||
         e == "KHR_materials_emissive_strength" || e == "KHR_materials_unlit" || e == "KHR_draco_mesh_compression" ||
         e == "KHR_materials_ior" || e == "KHR_materials_specular";
}

// POSITION's values as the file holds them, checked before a node's
// matrix turns an infinity into NaNs in the message (checkSceneGeometry
// checks the world positions after).
void checkPositions(const Accessor& position, int index, const std::string& path) {
  for (size_t k = 0; k < position.count(); ++k) {
    const glm::vec3 v(position.at(k));
    if (std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate && std::abs(v.z) <= kMaxCoordinate) continue;
    char value[96];
    std::snprintf(value, sizeof value, "(%g, %g, %g)", v.x, v.y, v.z);
    fail(path, "POSITION accessor " + std::to_string(index) + " element " + std::to_string(k) + " " + value +
                   ": coordinates must be finite and within 1e15");
  }
}

glm::vec3 unit(glm::vec3 v) {
  const float l = glm::length(v);
  return l > 0.0f && std::isfinite(l) ? v / l : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

glm::mat4 localTransform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), glm::value_ptr(m));  // column-major, as glTF's
    return glm::mat4(m);
  }
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return glm::mat4(m);
}

// What the file lacks, where that is plain: no meshes, meshes without
// primitives (a "primitives" that is not an array reads as none), or no
// node of the scene drawing one.
std::string GltfReader::whyNoTriangles() const {
  if (model_.meshes.empty()) return ": it has no meshes";
  if (std::all_of(model_.meshes.begin(), model_.meshes.end(), [](const tinygltf::Mesh& m) { return m.primitives.empty(); }))
    return ": its meshes have no primitives array";
  if (std::none_of(model_.nodes.begin(), model_.nodes.end(), [](const tinygltf::Node& n) { return n.mesh >= 0; }))
    return ": no node draws a mesh";
  return "";
}

Scene GltfReader::read() {
  readMaterials();
  for (const tinygltf::Mesh& m : model_.meshes)
    for (const tinygltf::Primitive& p : m.primitives) {
      const size_t set = p.material >= 0 && size_t(p.material) < uvSets_.size() ? size_t(uvSets_[size_t(p.material)]) : 0;
      anyUv_ = anyUv_ || p.attributes.count("TEXCOORD_0") || p.attributes.count("TEXCOORD_" + std::to_string(set));
    }
  warnUnread();
  bool morphs = false;
  for (const tinygltf::Mesh& m : model_.meshes)
    for (const tinygltf::Primitive& p : m.primitives) morphs = morphs || !p.targets.empty();
  if (!model_.animations.empty() || !model_.skins.empty() || morphs) animation_ = std::make_shared<SceneAnimation>();
  onPath_.assign(model_.nodes.size(), false);
  for (int r : roots()) node(r, glm::mat4(1.0f), -1);
  if (!marks_.empty()) {
    addPointLineSolids(scene_, marks_);
    warn_("points and lines drawn as small solids (mvr/assets/point_line_solids.h)");
  }
  if (scene_.triangles.empty()) fail(path_, "glTF scene has no triangles" + whyNoTriangles());
  if (animation_) {
    readSkins();
    // Skins and morph weights at rest give the shape the file shows.
    if (!model_.skins.empty() || morphs) animation_->pose(scene_.positions, scene_.normals, 0.0, -2, glm::mat4(1.0f));
    readClips();
  }
  addLights();
  scene_.source = path_;
  return std::move(scene_);
}

// The default scene's roots (else the first scene's; else every node no
// node names as its child).
std::vector<int> GltfReader::roots() const {
  if (!model_.scenes.empty()) {
    const size_t s = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size()
                         ? size_t(model_.defaultScene) : 0;
    return model_.scenes[s].nodes;
  }
  std::vector<bool> child(model_.nodes.size(), false);
  for (const tinygltf::Node& n : model_.nodes)
    for (int c : n.children)
      if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
  std::vector<int> roots;
  for (size_t i = 0; i < child.size(); ++i)
    if (!child[i]) roots.push_back(int(i));
  return roots;
}

// What the file uses that is not read: a warning each.
void GltfReader::warnUnread() {
  for (const std::string& e : model_.extensionsRequired)
    if (!isRead(e)) warn_("requires the extension " + e + ", which is not read: drawn without it");
  for (const std::string& e : model_.extensionsUsed)
    if (!isRead(e) && std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), e) == model_.extensionsRequired.end())
      warn_("uses the extension " + e + ", which is not read: drawn without it");
  for (const tinygltf::Material& g : model_.materials) {
    if (g.normalTexture.index >= 0) warn_("normalTexture not read: drawn with the vertex normals");
    if (g.occlusionTexture.index >= 0) warn_("occlusionTexture not read: drawn unoccluded");
    if (g.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
      warn_("metallicRoughnessTexture drawn as its mean roughness and metalness");
  }
}

// parentSlot: the parent's place in the animation's node list (-1: a root).
void GltfReader::node(int index, const glm::mat4& parent, int parentSlot) {
  if (index < 0 || size_t(index) >= model_.nodes.size()) fail(path_, "node " + std::to_string(index) + " does not exist");
  if (onPath_[size_t(index)]) fail(path_, "node " + std::to_string(index) + " is its own ancestor");
  onPath_[size_t(index)] = true;
  const tinygltf::Node& n = model_.nodes[size_t(index)];
  const glm::mat4 world = parent * localTransform(n);
  const int slot = animation_ ? animatedNode(index, parentSlot) : -1;
  currentNode_ = index;
  if (n.mesh >= 0) {
    if (size_t(n.mesh) >= model_.meshes.size()) fail(path_, "mesh " + std::to_string(n.mesh) + " does not exist");
    for (const tinygltf::Primitive& p : model_.meshes[size_t(n.mesh)].primitives) {
      if (animation_) {
        instance_ = &animation_->instances.emplace_back();
        instance_->node = slot;
        instance_->first = uint32_t(scene_.positions.size());
        instance_->skin = n.skin;  // the file's; ours after readSkins
      }
      primitive(p, world);
      instance_ = nullptr;
    }
  }
  if (n.camera >= 0) camera(n, world);
  if (const auto light = n.extensions.find("KHR_lights_punctual"); light != n.extensions.end())
    placeLight(light->second, world);
  for (int c : n.children) node(c, world, slot);
  onPath_[size_t(index)] = false;
}

void GltfReader::camera(const tinygltf::Node& n, const glm::mat4& world) {
  if (size_t(n.camera) >= model_.cameras.size()) fail(path_, "camera " + std::to_string(n.camera) + " does not exist");
  const tinygltf::Camera& c = model_.cameras[size_t(n.camera)];
  if (c.type != "perspective") {
    warn_("orthographic cameras skipped");
    return;
  }
  const double yfov = c.perspective.yfov;
  if (!(yfov > 0.0 && yfov < 3.1)) fail(path_, "camera " + std::to_string(n.camera) + " has a yfov outside (0, 3.1)");
  const std::string name = !c.name.empty() ? c.name : !n.name.empty() ? n.name : "camera " + std::to_string(n.camera);
  scene_.fileCameras.push_back({name, world, yfov});
}

// The primitive's triangles as corner indices, by its mode.
std::vector<glm::uvec3> GltfReader::corners(const tinygltf::Primitive& p, size_t vertices) {
  std::vector<uint32_t> idx;
  if (const std::shared_ptr<const Accessor> a = indices(p)) {
    idx.resize(a->count());
    for (size_t k = 0; k < idx.size(); ++k)
      if ((idx[k] = a->index(k)) >= vertices) fail(path_, "index " + std::to_string(idx[k]) + " beyond the vertices");
  } else {
    idx.resize(vertices);
    for (size_t k = 0; k < vertices; ++k) idx[k] = uint32_t(k);
  }
  std::vector<glm::uvec3> out;
  const size_t n = idx.size();
  if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) {
    for (size_t k = 0; k + 2 < n; k += 3) out.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
  } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t k = 0; k + 2 < n; ++k) out.emplace_back(idx[k], idx[k + 1 + k % 2], idx[k + 2 - k % 2]);
  } else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (size_t k = 0; k + 2 < n; ++k) out.emplace_back(idx[k + 1], idx[k + 2], idx[0]);
  }
  return out;
}

std::shared_ptr<const Accessor> GltfReader::attribute(const tinygltf::Primitive& p, const std::string& name) {
  auto it = p.attributes.find(name);
  if (it == p.attributes.end()) return nullptr;
  if (draco_)
    if (const auto decoded = draco_->attributes.find(name); decoded != draco_->attributes.end()) return decoded->second;
  return std::make_shared<Accessor>(model_, it->second, path_);
}

std::shared_ptr<const Accessor> GltfReader::indices(const tinygltf::Primitive& p) {
  if (draco_ && draco_->indices) return draco_->indices;
  return p.indices >= 0 ? std::make_shared<Accessor>(model_, p.indices, path_) : nullptr;
}

void GltfReader::primitive(const tinygltf::Primitive& p, const glm::mat4& world) {
  if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    pointsAndLines(p, world);
    return;
  }
  draco_ = decodeDraco(model_, p, path_);
  const std::shared_ptr<const Accessor> position = attribute(p, "POSITION");
  if (!position) {
    warn_("a primitive without POSITION skipped");
    return;
  }
  if (position->components() != 3) fail(path_, "POSITION must be VEC3");
  checkPositions(*position, p.attributes.at("POSITION"), path_);
  const uint32_t materialId = p.material >= 0 && size_t(p.material) < scene_.materials.size() ? uint32_t(p.material)
                                                                                               : defaultMaterial();
  const int uvSet = materialId < uvSets_.size() ? uvSets_[materialId] : 0;
  const std::shared_ptr<const Accessor> normal = attribute(p, "NORMAL"), color = attribute(p, "COLOR_0"),
                                        uv = attribute(p, "TEXCOORD_" + std::to_string(uvSet));
  for (const auto& a : {normal, uv, color})
    if (a && a->count() != position->count()) fail(path_, "a primitive's attributes differ in count");
  if (normal && normal->components() != 3) fail(path_, "NORMAL must be VEC3");
  const Deformation deform = deformation(p, position->count(), normal != nullptr);
  std::vector<glm::uvec3> tris = corners(p, position->count());
  if (scene_.triangles.size() + tris.size() > kMaxTriangles) fail(path_, "more than 2^28 triangles");
  reserve(normal ? position->count() : 3 * tris.size(), tris.size());
  if (materialId < hidden_.size() && hidden_[materialId]) return;  // masked out whole
  const glm::mat3 uvTransform = materialId < uvTransforms_.size() ? uvTransforms_[materialId] : glm::mat3(1.0f);
  const glm::mat3 linear(world);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const bool mirrored = glm::determinant(linear) < 0.0f;
  auto vertex = [&](uint32_t k, const glm::vec3& n, const glm::vec3& local) {
    scene_.positions.push_back(glm::vec3(world * glm::vec4(glm::vec3(position->at(k)), 1.0f)));
    scene_.normals.push_back(n);
    if (instance_) {
      instance_->positions.push_back(glm::vec3(position->at(k)));
      instance_->normals.push_back(local);
      deform.add(k, *instance_);
    }
    if (anyUv_) {
      const glm::vec2 t = uv ? glm::vec2(uvTransform * glm::vec3(glm::vec2(uv->at(k)), 1.0f)) : glm::vec2(0.0f, 1.0f);
      scene_.uvs.emplace_back(t.x, 1.0f - t.y);  // glTF's v runs down the image, ours up
    }
    scene_.colors.push_back(color ? glm::clamp(glm::vec3(color->at(k)), 0.0f, 1.0f) : glm::vec3(1.0f));
  };
  if (normal) {
    const auto base = uint32_t(scene_.positions.size());
    for (uint32_t k = 0; k < uint32_t(position->count()); ++k)
      vertex(k, unit(normalMatrix * glm::vec3(normal->at(k))), glm::vec3(normal->at(k)));
    for (glm::uvec3 t : tris) add(t + base, mirrored, materialId);
    return;
  }
  // No normals: flat ones (the spec), so each triangle its own corners.
  if (instance_) instance_->flat = true;
  for (glm::uvec3 t : tris) {
    if (mirrored) std::swap(t.y, t.z);
    const glm::vec3 la(position->at(t.x)), lb(position->at(t.y)), lc(position->at(t.z));
    const glm::vec3 a = glm::vec3(world * glm::vec4(la, 1.0f)), b = glm::vec3(world * glm::vec4(lb, 1.0f)),
                    c = glm::vec3(world * glm::vec4(lc, 1.0f));
    const glm::vec3 n = unit(glm::cross(b - a, c - a));
    // world's n in the node's space: the cross product moves by det(M) M^-T,
    // the normal matrix by M^-T.
    const glm::vec3 local = glm::cross(lb - la, lc - la) * (mirrored ? -1.0f : 1.0f);
    const auto base = uint32_t(scene_.positions.size());
    for (uint32_t k : {t.x, t.y, t.z}) vertex(k, n, local);
    add(glm::uvec3(base, base + 1, base + 2), false, materialId);
  }
}

// A primitive of points or lines (POINTS, LINES, LINE_LOOP, LINE_STRIP),
// in world coordinates, for the solids that draw them (unanimated).
void GltfReader::pointsAndLines(const tinygltf::Primitive& p, const glm::mat4& world) {
  draco_ = decodeDraco(model_, p, path_);
  const std::shared_ptr<const Accessor> position = attribute(p, "POSITION");
  if (!position) return;
  if (position->components() != 3) fail(path_, "POSITION must be VEC3");
  const std::shared_ptr<const Accessor> color = attribute(p, "COLOR_0");
  if (color && color->count() != position->count()) fail(path_, "a primitive's attributes differ in count");
  if (instance_ && (instance_->skin >= 0 || !p.targets.empty())) warn_("skinned or morphed points and lines drawn at rest");
  const uint32_t material = p.material >= 0 && size_t(p.material) < scene_.materials.size() ? uint32_t(p.material)
                                                                                            : defaultMaterial();
  if (material < hidden_.size() && hidden_[material]) return;
  std::vector<uint32_t> idx;
  if (const std::shared_ptr<const Accessor> a = indices(p)) {
    for (size_t k = 0; k < a->count(); ++k)
      if (idx.push_back(a->index(k)); idx.back() >= position->count())
        fail(path_, "index " + std::to_string(idx.back()) + " beyond the vertices");
  } else {
    for (size_t k = 0; k < position->count(); ++k) idx.push_back(uint32_t(k));
  }
  auto mark = [&](uint32_t k) {
    const glm::vec3 c = color ? glm::clamp(glm::vec3(color->at(k)), 0.0f, 1.0f) : glm::vec3(1.0f);
    return PointLineSet::Mark{glm::vec3(world * glm::vec4(glm::vec3(position->at(k)), 1.0f)), c};
  };
  const size_t n = idx.size();
  if (p.mode == TINYGLTF_MODE_POINTS) {
    for (uint32_t k : idx) marks_.addPoint(mark(k), material);
  } else if (p.mode == TINYGLTF_MODE_LINE) {
    for (size_t k = 0; k + 1 < n; k += 2) marks_.addSegment(mark(idx[k]), mark(idx[k + 1]), material);
  } else if (p.mode == TINYGLTF_MODE_LINE_STRIP || p.mode == TINYGLTF_MODE_LINE_LOOP) {
    for (size_t k = 0; k + 1 < n; ++k) marks_.addSegment(mark(idx[k]), mark(idx[k + 1]), material);
    if (p.mode == TINYGLTF_MODE_LINE_LOOP && n > 2) marks_.addSegment(mark(idx[n - 1]), mark(idx[0]), material);
  } else {
    warn_("a primitive of unknown mode " + std::to_string(p.mode) + " skipped");
  }
}

// Room for a primitive more, growing geometrically: a file of many
// primitives reallocates as often as push_back would, one of a few
// large ones not at all.
void GltfReader::reserve(size_t vertices, size_t triangles) {
  auto grow = [](auto& v, size_t more) {
    if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
  };
  grow(scene_.positions, vertices), grow(scene_.normals, vertices), grow(scene_.colors, vertices);
  if (anyUv_) grow(scene_.uvs, vertices);
  grow(scene_.triangles, triangles), grow(scene_.materialIds, triangles);
}

void GltfReader::add(glm::uvec3 t, bool mirrored, uint32_t materialId) {
  if (t.x == t.y || t.y == t.z || t.x == t.z) {
    ++scene_.droppedFaces;
    return;
  }
  if (mirrored) std::swap(t.y, t.z);
  scene_.triangles.push_back(t);
  scene_.materialIds.push_back(materialId);
}

uint32_t GltfReader::defaultMaterial() {
  if (defaultMaterial_ < 0) {
    defaultMaterial_ = int(scene_.materials.size());
    Material m;
    m.setMetallicRoughness(glm::vec3(1.0f), 1.0f, 1.0f);  // the spec's default: a white, rough metal
    m.twoSided = false;
    scene_.materials.push_back(m);
  }
  return uint32_t(defaultMaterial_);
}

}  // namespace mvr::gltf
