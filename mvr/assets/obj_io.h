#pragma once
// Wavefront OBJ with its MTL materials, read by tinyobjloader (Debian's
// libtinyobjloader: maintained, and reads MTL, which OpenMesh's OBJ reader
// reduces to one colour per face; docs/ARCHITECTURE.md).
#include <string>

#include "mvr/scene.h"

namespace mvr {

// The file's faces (polygons triangulated), with a vertex per distinct
// position, texture coordinate and normal a corner names. Normals: the
// file's where every corner has one, else smooth ones over each position
// (so that a texture seam is not a shading seam). Vertex colours
// ("v x y z r g b") as OpenMesh read them. Materials from the MTL files
// `mtllib` names, per `usemtl` group: Kd diffuse, Ks specular, Ns
// shininess, map_Kd texture (the path relative to the MTL; backslashes
// and a case that differs from the disk's are tolerated with a warning).
// Faces of no material, or of one the MTL lacks, get the default one.
// Statements and MTL features not read are named once each in
// Scene::warnings. Throws mvr::Error naming the file and the problem.
Scene loadObj(const std::string& path);

}  // namespace mvr
