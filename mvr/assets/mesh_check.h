#pragma once
// Checks a mesh file before a library reads it. OpenMesh's readers trust
// their input: a PLY header with a mangled keyword crashes its format
// probe, one cut inside the header makes it spin, and one cut inside its
// data loses faces silently (issue 16); an OBJ face naming a vertex that
// does not exist corrupted its heap. These checks are bounded and read
// the file once; each rejection is one line naming the file and the line
// or element, which the libraries' own messages do not.
#include <istream>
#include <string>
#include <utility>
#include <vector>

#include "mvr/scene.h"

namespace mvr {

// The largest coordinate a scene may hold: products of two coordinates
// (normals, areas) stay finite in float.
inline constexpr float kMaxCoordinate = 1e15f;
// How far beyond the extent of the bulk of the vertices (1st to 99th
// percentile per axis) one may stray: a vertex farther out would frame the
// camera so wide that the rest shrinks below a pixel.
inline constexpr double kMaxOutlier = 1e6;

// Numbers a loaded scene must satisfy, named by `where` (the file):
// coordinates finite and within kMaxCoordinate, no stray vertex beyond
// kMaxOutlier times the bulk's extent, and at least one triangle of
// non-zero area. Throws mvr::Error naming the vertex.
void checkSceneGeometry(const Scene& scene, const std::string& where);

// The PLY header lines OpenMesh would misread, to be handed to it as
// comments (by their line numbers). OpenMesh reads the header word by word:
// a line that starts with no keyword (old Blender wrote "Created by
// Blender3D ..." bare; a defect worth a warning) stops it, and the words
// of an obj_info line (free text) that are header keywords it obeys.
struct PlyCommentLines {
  std::vector<long> bare, info;  // each ascending, as the header is read
  // Both, ascending.
  std::vector<long> all() const;
};

// OBJ: every v/vt/vn reference of every face in range of the elements
// defined before it (negative indices count back), at least three corners
// per face. PLY: a complete header (ply, one format line, elements with
// counts, properties of known types, end_header), and data long enough for
// every element (binary: at least each element's fixed bytes; ASCII: a
// line per element). OFF: its vertex and face counts within what the data
// after them can hold. STL passes. Throws mvr::Error.
void checkMeshFile(const std::string& path, PlyCommentLines* comments = nullptr);

// What an OBJ file says that is not drawn: statements other than v, vt,
// vn, f, g, o, s, usemtl and mtllib (keyword and first line, the first few
// met), and whether it has points or lines. And whether a usemtl names a
// material of several words (3ds Max writes "Material #25").
struct ObjStatements {
  std::vector<std::pair<std::string, long>> ignored;
  bool pointsOrLines = false;
  bool spacedNames = false;
};

// The OBJ checks of checkMeshFile, noting the statements not drawn; of
// the file's text as read from `in` (path: for errors).
void checkObjFile(const std::string& path, ObjStatements* notes);
void checkObjText(std::istream& in, const std::string& path, ObjStatements* notes);

}  // namespace mvr
