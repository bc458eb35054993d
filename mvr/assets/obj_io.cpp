#include "mvr/assets/obj_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include <tiny_obj_loader.h>

#include "mvr/error.h"
#include "mvr/files/file_search.h"
#include "mvr/assets/load_warnings.h"
#include "mvr/assets/mesh_check.h"
#include "mvr/assets/point_line_solids.h"
#include "mvr/files/text_encoding.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;


// tinyobjloader reads a newmtl name to the end of its line but a usemtl
// name to its first blank: where a file names materials of several words,
// both are read with their blanks as kJoin, which Material::name turns
// back.
constexpr char kJoin = '\x1f';

std::string joined(const std::string& name) {
  const size_t first = name.find_first_not_of(" \t\r"), last = name.find_last_not_of(" \t\r");
  std::string out = first == std::string::npos ? "" : name.substr(first, last - first + 1);
  std::replace_if(out.begin(), out.end(), [](char c) { return c == ' ' || c == '\t'; }, kJoin);
  return out;
}

// The OBJ's text with each usemtl name joined.
std::string withJoinedNames(std::istream& in) {
  std::string out;
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find_first_not_of(" \t");
    if (at != std::string::npos && line.compare(at, 7, "usemtl ") == 0) line = "usemtl " + joined(line.substr(at + 7));
    out += line + '\n';
  }
  return out;
}

// The MTL files `mtllib` names, found from the OBJ's folder as findFile
// tolerates; remembers each material's folder, where its maps are.
class MtlFiles final : public tinyobj::MaterialReader {
 public:
  MtlFiles(fs::path dir, LoadWarnings& warn, bool join) : dir_(std::move(dir)), warn_(warn), join_(join) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* ids, std::string* warn, std::string* err) override {
    std::string how;
    bool backslashes = false;
    const std::string file = findFile(dir_, name, how, backslashes);
    if (file.empty()) {
      warn_("material library '" + name + "' not found: its materials are drawn as the default");
      return false;
    }
    if (!how.empty()) warn_("material library '" + name + "' read " + how);
    if (backslashes) warn_("backslashes in file names read as slashes");
    std::ifstream in(file);
    const size_t first = materials->size();
    tinyobj::LoadMtl(ids, materials, &in, warn, err);
    folders.resize(materials->size(), fs::path(file).parent_path());
    for (size_t i = first; join_ && i < materials->size(); ++i) {
      tinyobj::material_t& m = (*materials)[i];
      ids->erase(m.name);
      m.name = joined(m.name);
      (*ids)[m.name] = int(i);
    }
    return true;
  }

  std::vector<fs::path> folders;  // per material

 private:
  fs::path dir_;
  LoadWarnings& warn_;
  bool join_;
};

glm::vec3 unitColor(const tinyobj::real_t (&c)[3], const std::string& what, LoadWarnings& warn) {
  glm::vec3 v(c[0], c[1], c[2]);
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(v[k])) v[k] = 0.0f;
  if (!isUnitColor(v)) warn(what + " outside [0, 1] clamped");
  return glm::clamp(v, 0.0f, 1.0f);
}

// A texture map an MTL names, found beside it (or "" with a warning).
// `without`: how the surface is drawn then.
std::string mapFile(const fs::path& folder, const std::string& name, const tinyobj::texture_option_t& o,
                    const std::string& key, const char* without, LoadWarnings& warn) {
  std::string how;
  bool backslashes = false;
  const std::string file = findFile(folder, name, how, backslashes);
  if (file.empty()) warn(key + " '" + name + "' not found: " + without);
  if (!how.empty()) warn(key + " '" + name + "' read " + how);
  if (backslashes) warn("backslashes in file names read as slashes");
  if (o.scale[0] != 1 || o.scale[1] != 1 || o.origin_offset[0] != 0 || o.origin_offset[1] != 0)
    warn(key + " options -s and -o not read");
  return file;
}

// One MTL material as ours: Kd the diffuse colour (map_Kd multiplies it,
// as the MTL format says), Ks and Ns the Blinn-Phong highlight, Ke the
// emission (map_Ke multiplies it). What an MTL says that our model has no
// place for is named in a warning.
Material materialOf(const tinyobj::material_t& t, const fs::path& folder, LoadWarnings& warn) {
  Material m;
  m.name = t.name;
  std::replace(m.name.begin(), m.name.end(), kJoin, ' ');
  const std::string of = "material '" + m.name + "': ";
  m.diffuse = unitColor(t.diffuse, of + "Kd", warn);
  m.specular = unitColor(t.specular, of + "Ks", warn);
  m.shininess = std::isfinite(t.shininess) ? std::clamp(float(t.shininess), 1.0f, 1e4f) : 1.0f;
  if (!t.diffuse_texname.empty())
    m.texture = mapFile(folder, t.diffuse_texname, t.diffuse_texopt, of + "map_Kd", "drawn untextured", warn);
  if (t.dissolve < 1.0f) warn(of + "transparency (d, Tr) drawn opaque");
  m.emission = unitColor(t.emission, of + "Ke", warn);
  if (!t.emissive_texname.empty() && m.emission != glm::vec3(0.0f))
    m.emissionTexture = mapFile(folder, t.emissive_texname, t.emissive_texopt, of + "map_Ke",
                                "its emission drawn untextured", warn);
  std::vector<std::string> unread;
  auto note = [&](const std::string& map, const char* key) {
    if (!map.empty()) unread.push_back(key);
  };
  note(t.specular_texname, "map_Ks"), note(t.specular_highlight_texname, "map_Ns");
  note(t.bump_texname, "bump"), note(t.normal_texname, "norm"), note(t.displacement_texname, "disp");
  note(t.alpha_texname, "map_d"), note(t.reflection_texname, "refl");
  for (const auto& [key, value] : t.unknown_parameter) unread.push_back(key.substr(0, 24));
  if (!unread.empty()) {
    std::string list;
    for (const std::string& k : unread) list += (list.empty() ? "" : ", ") + k;
    warn(of + "not read: " + list);
  }
  return m;
}

// A triangle corner's vertex: position, texture coordinate and normal
// indices (-1 for none), as one key.
struct CornerKey {
  int v, t, n;
  bool operator==(const CornerKey&) const = default;
};
struct CornerHash {
  size_t operator()(const CornerKey& k) const {
    return (size_t(uint32_t(k.v)) * 0x9E3779B97F4A7C15ull) ^ (size_t(uint32_t(k.t)) * 0xC2B2AE3D27D4EB4Full) ^
           size_t(uint32_t(k.n));
  }
};

class ObjBuilder {
 public:
  ObjBuilder(const tinyobj::attrib_t& a, const std::vector<tinyobj::material_t>& materials,
             const std::vector<fs::path>& folders, const std::string& path, Scene& scene, LoadWarnings& warn)
      : a_(a), materials_(materials), folders_(folders), path_(path), scene_(scene), warn_(warn) {}

  void build(const std::vector<tinyobj::shape_t>& shapes) {
    checkAttributes();
    for (const tinyobj::shape_t& s : shapes) note(s.mesh);
    for (const tinyobj::shape_t& s : shapes) faces(s.mesh);
    if (!allNormals_) smoothNormals();
    PointLineSet marks;
    for (const tinyobj::shape_t& s : shapes) pointsAndLines(s, marks);
    if (marks.empty() && scene_.triangles.empty() && !scene_.droppedFaces) {
      // Vertices and nothing else (a scanner's point cloud, as Meshlab saves one).
      for (size_t v = 0; v < a_.vertices.size() / 3; ++v) marks.addPoint({position(v), color(v)}, material(-1, false));
      if (!marks.empty()) warn_("a point cloud: its vertices drawn as small solids (mvr/assets/point_line_solids.h)");
    }
    addPointLineSolids(scene_, marks);
  }

 private:
  // Smooth normals over each position, shared by its copies.
  void smoothNormals() {
    Scene byPosition;
    for (size_t v = 0; v < a_.vertices.size() / 3; ++v) byPosition.positions.push_back(position(v));
    byPosition.triangles = positionTriangles_;
    computeVertexNormals(byPosition);
    scene_.normals.clear();
    for (int v : vertexPosition_) scene_.normals.push_back(byPosition.normals[size_t(v)]);
  }

  // A shape's `p` and `l` statements (l: polylines), in the default material.
  void pointsAndLines(const tinyobj::shape_t& s, PointLineSet& marks) {
    const int vertices = int(a_.vertices.size() / 3);
    auto mark = [&](const tinyobj::index_t& i) {
      if (i.vertex_index < 0 || i.vertex_index >= vertices) fail(path_, "a point or line refers to a vertex that does not exist");
      return PointLineSet::Mark{position(size_t(i.vertex_index)), color(size_t(i.vertex_index))};
    };
    if (s.points.indices.empty() && s.lines.indices.empty()) return;
    const uint32_t m = material(-1, false);
    for (const tinyobj::index_t& i : s.points.indices) marks.addPoint(mark(i), m);
    size_t at = 0;
    for (int count : s.lines.num_line_vertices) {
      for (int k = 0; k + 1 < count && at + size_t(k) + 1 < s.lines.indices.size(); ++k)
        marks.addSegment(mark(s.lines.indices[at + size_t(k)]), mark(s.lines.indices[at + size_t(k) + 1]), m);
      at += size_t(std::max(count, 0));
    }
  }
  glm::vec3 position(size_t v) const { return {a_.vertices[3 * v], a_.vertices[3 * v + 1], a_.vertices[3 * v + 2]}; }
  glm::vec3 color(size_t v) const {
    return 3 * v + 2 < a_.colors.size() ? glm::vec3(a_.colors[3 * v], a_.colors[3 * v + 1], a_.colors[3 * v + 2]) : glm::vec3(1.0f);
  }

  void checkAttributes() {
    for (size_t v = 0; v < a_.vertices.size() / 3; ++v) {
      const glm::vec3 p = position(v);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(path_, "vertex " + std::to_string(v) + " has a non-finite coordinate");
      if (3 * v + 2 < a_.colors.size() &&
          !isUnitColor({a_.colors[3 * v], a_.colors[3 * v + 1], a_.colors[3 * v + 2]}))
        fail(path_, "vertex " + std::to_string(v) + " has a colour outside [0, 1]");
    }
  }

  // Whether every corner has a normal and any a texture coordinate; every
  // index in range (tinyobjloader does not check a triangle's).
  void note(const tinyobj::mesh_t& m) {
    const int vertices = int(a_.vertices.size() / 3), uvs = int(a_.texcoords.size() / 2),
              normals = int(a_.normals.size() / 3);
    for (const tinyobj::index_t& i : m.indices) {
      if (i.vertex_index < 0 || i.vertex_index >= vertices || i.texcoord_index < -1 || i.texcoord_index >= uvs ||
          i.normal_index < -1 || i.normal_index >= normals)
        fail(path_, "a face refers to an element that does not exist");
      allNormals_ = allNormals_ && i.normal_index >= 0;
      anyUv_ = anyUv_ || i.texcoord_index >= 0;
    }
  }

  void faces(const tinyobj::mesh_t& m) {
    size_t at = 0;
    for (size_t f = 0; f < m.num_face_vertices.size(); at += m.num_face_vertices[f], ++f) {
      if (m.num_face_vertices[f] != 3 || at + 3 > m.indices.size()) {
        ++scene_.droppedFaces;
        continue;
      }
      const tinyobj::index_t* c = &m.indices[at];
      if (c[0].vertex_index == c[1].vertex_index || c[1].vertex_index == c[2].vertex_index ||
          c[0].vertex_index == c[2].vertex_index) {
        ++scene_.droppedFaces;
        continue;
      }
      glm::uvec3 t;
      for (int k = 0; k < 3; ++k) t[k] = vertex(c[k]);  // in order: vertices numbered as first met
      scene_.triangles.push_back(t);
      positionTriangles_.emplace_back(c[0].vertex_index, c[1].vertex_index, c[2].vertex_index);
      scene_.materialIds.push_back(material(f < m.material_ids.size() ? m.material_ids[f] : -1));
    }
  }

  uint32_t vertex(const tinyobj::index_t& i) {
    const CornerKey key{i.vertex_index, anyUv_ ? i.texcoord_index : -1, allNormals_ ? i.normal_index : -1};
    auto [it, added] = vertexOf_.emplace(key, uint32_t(scene_.positions.size()));
    if (!added) return it->second;
    const auto v = size_t(i.vertex_index);
    scene_.positions.push_back(position(v));
    vertexPosition_.push_back(i.vertex_index);
    scene_.colors.push_back(color(v));
    if (anyUv_) {
      const auto t = size_t(key.t);
      scene_.uvs.push_back(key.t >= 0 ? glm::vec2(a_.texcoords[2 * t], a_.texcoords[2 * t + 1]) : glm::vec2(0.0f));
    }
    if (allNormals_) {
      const auto n = size_t(key.n);
      const glm::dvec3 normal(a_.normals[3 * n], a_.normals[3 * n + 1], a_.normals[3 * n + 2]);
      const double len = glm::length(normal);  // double: a length of 1e20 squared overflows float
      scene_.normals.push_back(std::isfinite(len) && len > 0 ? glm::vec3(normal / len) : glm::vec3(0, 0, 1));
    }
    return it->second;
  }

  // Our material for the file's (-1: none), each added when first used.
  uint32_t material(int id, bool faces = true) {
    if (id < 0 || size_t(id) >= materials_.size()) {
      if (!materials_.empty() && faces) warn_("faces of no material the MTL files define are drawn as the default");
      id = -1;
    }
    auto [it, added] = materialOf_.emplace(id, uint32_t(scene_.materials.size()));
    if (added)
      scene_.materials.push_back(id < 0 ? Material{}
                                        : materialOf(materials_[size_t(id)], folders_[size_t(id)], warn_));
    return it->second;
  }

  const tinyobj::attrib_t& a_;
  const std::vector<tinyobj::material_t>& materials_;
  const std::vector<fs::path>& folders_;
  const std::string& path_;
  Scene& scene_;
  LoadWarnings& warn_;
  bool allNormals_ = true, anyUv_ = false;
  std::unordered_map<CornerKey, uint32_t, CornerHash> vertexOf_;
  std::map<int, uint32_t> materialOf_;
  std::vector<int> vertexPosition_;           // per vertex: its position's index
  std::vector<glm::uvec3> positionTriangles_;  // the triangles by position
};

void warnStatements(const ObjStatements& notes, LoadWarnings& warn) {
  if (notes.pointsOrLines) warn("points and lines drawn as small solids (mvr/assets/point_line_solids.h)");
  if (notes.ignored.empty()) return;
  std::string list;
  for (const auto& [key, line] : notes.ignored)
    list += (list.empty() ? "" : ", ") + key + " (line " + std::to_string(line) + ")";
  warn("statements not read: " + list);
}

}  // namespace

Scene loadObj(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail(path, "no such mesh file");
  // A UTF-16 file's text, as UTF-8, read from memory; any other's from the file.
  const bool utf16 = isUtf16(fileStart(path, 2));
  std::istringstream utf8(utf16 ? utf8OfUtf16File(path) : "");
  std::ifstream file(path, std::ios::binary);
  std::istream& source = utf16 ? static_cast<std::istream&>(utf8) : file;
  ObjStatements notes;
  checkObjText(source, path, &notes);  // names the line of a bad index or number, which tinyobjloader does not
  source.clear(), source.seekg(0);
  Scene scene;
  scene.source = path;
  LoadWarnings warn(scene, path);
  if (utf16) warn("UTF-16 text read as UTF-8");
  warnStatements(notes, warn);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string tinyWarn, error;
  MtlFiles mtl(fs::path(path).parent_path(), warn, notes.spacedNames);
  std::istringstream joined(notes.spacedNames ? withJoinedNames(source) : "");
  std::istream& in = notes.spacedNames ? static_cast<std::istream&>(joined) : source;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &tinyWarn, &error, &in, &mtl, true, true))
    fail(path, error.empty() ? "cannot read OBJ" : error.substr(0, error.find('\n')));
  mtl.folders.resize(materials.size(), fs::path(path).parent_path());
  ObjBuilder(attrib, materials, mtl.folders, path, scene, warn).build(shapes);
  if (scene.triangles.empty())
    fail(path, scene.droppedFaces ? "mesh has no usable triangles (" + std::to_string(scene.droppedFaces) +
                                        " faces with repeated or missing corners)"
                                  : std::string("mesh has no triangles"));
  return scene;
}

}  // namespace mvr
