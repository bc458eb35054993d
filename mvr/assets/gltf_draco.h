#pragma once
// KHR_draco_mesh_compression: a primitive whose attributes and indices
// lie in one Draco-compressed buffer view, decoded by Google's draco
// library (Debian's libdraco) into accessors the reader uses as any other.
#include <map>
#include <memory>
#include <string>

#include <tiny_gltf.h>

#include "mvr/assets/gltf_accessor.h"

namespace mvr::gltf {

struct DracoPrimitive {
  std::map<std::string, std::shared_ptr<const Accessor>> attributes;  // by glTF name
  std::shared_ptr<const Accessor> indices;  // its triangles' corners (null: a point cloud)
};

// Debian's tinygltf is built without Draco, and refuses a compressed
// primitive's indices accessor, which has no buffer view: the file's JSON
// with those primitives' "indices" taken out (their corners come from the
// Draco data), or "" where no primitive needs it.
std::string withoutDracoIndices(const std::string& json);
// The same for a GLB file's bytes: the file rebuilt with that JSON, or ""
// where it is not needed.
std::string glbWithoutDracoIndices(const unsigned char* bytes, size_t size);

// The primitive's decoded data; null when it is not compressed. Throws
// mvr::Error naming the file when the data cannot be decoded.
std::unique_ptr<DracoPrimitive> decodeDraco(const tinygltf::Model& m, const tinygltf::Primitive& p, const std::string& path);

}  // namespace mvr::gltf
