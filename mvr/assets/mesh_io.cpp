#include "mvr/assets/mesh_io.h"

// GCC's middle end warns inside the library code OpenMesh's importer
// template instantiates here (std::construct_at of its colour vectors,
// memcpy in std::string); neither is ours to fix.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/ImporterT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "mvr/error.h"
#include "mvr/files/file_search.h"
#include "mvr/assets/assimp_import.h"
#include "mvr/assets/gltf_io.h"
#include "mvr/assets/mesh_check.h"
#include "mvr/assets/point_line_solids.h"
#include "mvr/assets/obj_io.h"

namespace mvr {
namespace {

struct Traits : OpenMesh::DefaultTraits {
  VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Color |
                   OpenMesh::Attributes::TexCoord2D);
  FaceAttributes(OpenMesh::Attributes::Normal);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;  // written: 8-bit colours

// Read with float colours: OpenMesh casts a float colour read from a file
// (OBJ "v x y z r g b", PLY float red) to 8 bits without clamping, which is
// undefined behaviour for 2.0 (found by fuzzing). As floats nothing is cast,
// and loadMesh checks the range itself.
struct ReadTraits : Traits {
  typedef OpenMesh::Vec3f Color;
};
using ReadMesh = OpenMesh::TriMesh_ArrayKernelT<ReadTraits>;

// OpenMesh's importer, counting the faces it refuses (a repeated corner, a
// vertex index out of range) instead of dropping them without a word, and
// noting which vertices the file gave a normal, colour or texture
// coordinate: the others hold whatever the property's memory held (an OBJ
// colouring only some vertices; the copies made for non-manifold faces).
class CheckedImporter final : public OpenMesh::IO::ImporterT<ReadMesh> {
 public:
  using ImporterT::ImporterT;
  using VertexHandle = OpenMesh::VertexHandle;
  OpenMesh::FaceHandle add_face(const VHandles& corners) override {
    OpenMesh::FaceHandle f = ImporterT::add_face(corners);
    if (!f.is_valid()) ++dropped;
    return f;
  }
  void set_normal(VertexHandle v, const OpenMesh::Vec3f& n) override { note(normals, v), ImporterT::set_normal(v, n); }
  void set_normal(VertexHandle v, const OpenMesh::Vec3d& n) override { note(normals, v), ImporterT::set_normal(v, n); }
  void set_color(VertexHandle v, const OpenMesh::Vec3uc& c) override { note(colors, v), ImporterT::set_color(v, c); }
  void set_color(VertexHandle v, const OpenMesh::Vec4uc& c) override { note(colors, v), ImporterT::set_color(v, c); }
  void set_color(VertexHandle v, const OpenMesh::Vec3f& c) override { note(colors, v), ImporterT::set_color(v, c); }
  void set_color(VertexHandle v, const OpenMesh::Vec4f& c) override { note(colors, v), ImporterT::set_color(v, c); }
  void set_texcoord(VertexHandle v, const OpenMesh::Vec2f& t) override { note(uvs, v), ImporterT::set_texcoord(v, t); }

  size_t dropped = 0;
  std::vector<bool> normals, colors, uvs;  // per vertex: given by the file

  static bool given(const std::vector<bool>& set, VertexHandle v) {
    return size_t(v.idx()) < set.size() && set[size_t(v.idx())];
  }

 private:
  static void note(std::vector<bool>& set, VertexHandle v) {
    if (!v.is_valid()) return;
    if (size_t(v.idx()) >= set.size()) set.resize(size_t(v.idx()) + 1, false);
    set[size_t(v.idx())] = true;
  }
};

void silenceOpenMesh() {
  // OpenMesh reports read problems on its own streams; ours are one line.
  omerr().disable();
  omlog().disable();
  omout().disable();
}

// The file with "comment " put before each of the header lines `lines`
// names (ascending), for OpenMesh. Held in memory: only odd files have such
// lines.
std::string withCommentedLines(const std::string& path, const std::vector<long>& lines) {
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t at = 0;
  long line = 1;
  for (long commented : lines) {
    for (; line < commented; ++line) at = text.find('\n', at) + 1;
    text.insert(at, "comment ");
  }
  return text;
}

// A file of vertices and no faces (a scanner's point cloud): its points
// drawn as small solids, in their colours.
Scene pointCloud(Scene s) {
  PointLineSet points;
  for (size_t v = 0; v < s.positions.size(); ++v) points.addPoint({s.positions[v], s.colors[v]}, 0);
  s.positions.clear(), s.normals.clear(), s.colors.clear(), s.uvs.clear();
  addPointLineSolids(s, points);
  s.warnings.push_back(s.source + ": a point cloud: its points drawn as small solids (mvr/assets/point_line_solids.h)");
  return s;
}

}  // namespace

Scene loadMesh(const std::string& path) {
  if (isGltfPath(path)) return loadGltf(path);
  if (lowerExtension(path) == ".obj") return loadObj(path);
  if (isAssimpPath(path)) return importWithAssimp(path);
  if (const std::string ext = lowerExtension(path); ext != ".ply" && ext != ".off" && ext != ".stl")
    fail(path, "not a model format mvr reads ('" + ext + "'): it reads glTF (.gltf, .glb), OBJ, PLY, OFF, STL, FBX, "
               "Collada (.dae), 3DS and JSON scene files");
  silenceOpenMesh();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such mesh file");
  PlyCommentLines comments;
  checkMeshFile(path, &comments);  // OpenMesh trusts its input; this does not
  const std::vector<long>& bareLines = comments.bare;
  const std::vector<long> commented = comments.all();
  ReadMesh mesh;
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal |
                              OpenMesh::IO::Options::VertexColor |
                              OpenMesh::IO::Options::VertexTexCoord;
  CheckedImporter importer(mesh);
  bool read = false;
  if (commented.empty()) {
    read = OpenMesh::IO::IOManager().read(path, importer, opt);
  } else {
    std::istringstream text(withCommentedLines(path, commented));
    read = OpenMesh::IO::IOManager().read(text, ".ply", importer, opt);
  }
  if (!read) fail(path, "cannot read mesh (unsupported format or broken file)");
  const size_t dropped = importer.dropped;
  if (mesh.n_faces() == 0 && (dropped || mesh.n_vertices() == 0))
    fail(path, dropped ? "mesh has no usable triangles (" + std::to_string(dropped) +
                             " faces with repeated or missing corners)"
                       : std::string("mesh has no triangles"));
  Scene s;
  s.source = path;
  s.droppedFaces = dropped;
  if (!bareLines.empty())
    s.warnings.push_back(path + ":" + std::to_string(bareLines[0]) + ": PLY header line" +
                         (bareLines.size() > 1 ? "s with no keyword (" + std::to_string(bareLines.size()) + ")"
                                               : " with no keyword") +
                         " taken as a comment");
  s.positions.reserve(mesh.n_vertices());
  // A vertex the file gave no normal (or texture coordinate) means none for
  // the mesh: normals are then computed for all; no colour means white.
  bool fileNormals = opt.vertex_has_normal(), fileUvs = opt.vertex_has_texcoord();
  for (auto v : mesh.vertices()) {
    fileNormals = fileNormals && CheckedImporter::given(importer.normals, v);
    fileUvs = fileUvs && CheckedImporter::given(importer.uvs, v);
  }
  for (auto v : mesh.vertices()) {
    auto p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      fail(path, "vertex " + std::to_string(v.idx()) + " has a non-finite coordinate");
    s.positions.emplace_back(p[0], p[1], p[2]);
    if (fileNormals) {
      auto n = mesh.normal(v);
      const glm::dvec3 normal(n[0], n[1], n[2]);  // double: the length of 1e20 squared overflows float
      const double len = glm::length(normal);
      s.normals.push_back(std::isfinite(len) && len > 0 ? glm::vec3(normal / len) : glm::vec3(0, 0, 1));
    }
    glm::vec3 color(1.0f);
    if (opt.vertex_has_color() && CheckedImporter::given(importer.colors, v)) {
      auto c = mesh.color(v);
      color = glm::vec3(c[0], c[1], c[2]);  // 8-bit sources arrive divided by 255
      if (!isUnitColor(color)) fail(path, "vertex " + std::to_string(v.idx()) + " has a colour outside [0, 1]");
    }
    s.colors.push_back(color);
    if (fileUvs) {
      auto t = mesh.texcoord2D(v);
      s.uvs.emplace_back(t[0], t[1]);
    }
  }
  for (auto f : mesh.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto v : mesh.fv_range(f)) t[k++] = unsigned(v.idx());
    s.triangles.push_back(t);
  }
  s.materialIds.assign(s.triangles.size(), 0);
  s.materials.emplace_back();
  if (s.triangles.empty()) return pointCloud(std::move(s));
  if (!fileNormals) computeVertexNormals(s);
  return s;
}

void saveMeshPly(const Scene& scene, const std::string& path) {
  silenceOpenMesh();
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handles;
  for (size_t i = 0; i < scene.positions.size(); ++i) {
    const glm::vec3& p = scene.positions[i];
    auto h = mesh.add_vertex({p.x, p.y, p.z});
    const glm::vec3& n = scene.normals[i];
    mesh.set_normal(h, {n.x, n.y, n.z});
    const glm::vec3& c = scene.colors[i];
    glm::vec3 q = glm::round(glm::clamp(c, 0.0f, 1.0f) * 255.0f);
    mesh.set_color(h, TriMesh::Color(q.r, q.g, q.b));
    handles.push_back(h);
  }
  for (const glm::uvec3& t : scene.triangles)
    mesh.add_face(handles[t.x], handles[t.y], handles[t.z]);
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::VertexNormal |
                              OpenMesh::IO::Options::VertexColor;
  if (!OpenMesh::IO::write_mesh(mesh, path, opt)) fail(path, "cannot write mesh");
}

}  // namespace mvr
