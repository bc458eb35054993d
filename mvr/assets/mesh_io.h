#pragma once
// Triangle meshes: PLY, OFF and STL through OpenMesh; OBJ (obj_io.h) and
// glTF (gltf_io.h) through their own readers.
#include <string>

#include "mvr/scene.h"

namespace mvr {

// One mesh as a Scene with one default material. Normals are computed when
// the file has none; vertex colours default to white. Throws mvr::Error
// naming the file for a missing, unreadable, empty or non-finite mesh.
Scene loadMesh(const std::string& path);

// Writes positions, normals and colours as binary PLY (asset generators).
void saveMeshPly(const Scene& mesh, const std::string& path);

}  // namespace mvr
