#pragma once
// glTF 2.0 files (.gltf with its buffers and images, data URIs, .glb),
// read by tinygltf (Debian's libtinygltf: a maintained, single-purpose
// reader; docs/ARCHITECTURE.md says why).
#include <string>

#include "mvr/scene.h"

namespace mvr {

// The default scene (else the first; else every root node): each node's
// mesh drawn at its world transform (TRS or matrix, down the hierarchy; a
// mesh several nodes use, at each). Primitives of mode TRIANGLES,
// TRIANGLE_STRIP and TRIANGLE_FAN with any index type; points and lines
// are skipped with a warning. POSITION, NORMAL (flat normals where a
// primitive has none, as the spec asks), TEXCOORD_0, COLOR_0. Materials:
// baseColorFactor and baseColorTexture as diffuse and texture,
// metallic-roughness as our specular model (gltf_io.cpp has the mapping),
// doubleSided as two_sided. Throws mvr::Error naming the file and the
// problem; what is read other than as written goes to Scene::warnings.
Scene loadGltf(const std::string& path);

bool isGltfPath(const std::string& path);

}  // namespace mvr
