#include "mvr/assets/gltf_draco.h"

#include <cstring>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr::gltf {

std::string withoutDracoIndices(const std::string& text) {
  if (text.find("KHR_draco_mesh_compression") == std::string::npos) return "";
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return "";
  bool changed = false;
  for (auto& mesh : j["meshes"])
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
      for (auto& p : mesh["primitives"])
        if (p.is_object() && p.contains("extensions") && p["extensions"].is_object() &&
            p["extensions"].contains("KHR_draco_mesh_compression") && p.contains("indices")) {
          p.erase("indices");
          changed = true;
        }
  return changed ? j.dump() : "";
}

// GLB: a 12-byte header (magic, version 2, length), then chunks of
// (length, type, data): JSON first, then the binary one.
std::string glbWithoutDracoIndices(const unsigned char* bytes, size_t size) {
  auto word = [&](size_t at) {
    uint32_t w;
    std::memcpy(&w, bytes + at, 4);
    return w;
  };
  if (size < 20 || std::memcmp(bytes, "glTF", 4) != 0 || word(4) != 2 || word(16) != 0x4e4f534a) return "";
  const size_t jsonLength = word(12);
  if (jsonLength > size - 20) return "";
  std::string json = withoutDracoIndices(std::string(reinterpret_cast<const char*>(bytes + 20), jsonLength));
  if (json.empty()) return "";
  while (json.size() % 4) json += ' ';
  const size_t rest = 20 + jsonLength;
  std::string out(reinterpret_cast<const char*>(bytes), 20);
  out += json;
  out.append(reinterpret_cast<const char*>(bytes + rest), size - rest);
  const uint32_t total = uint32_t(out.size()), chunk = uint32_t(json.size());
  std::memcpy(out.data() + 8, &total, 4);
  std::memcpy(out.data() + 12, &chunk, 4);
  return out;
}

std::unique_ptr<DracoPrimitive> decodeDraco(const tinygltf::Model& m, const tinygltf::Primitive& p, const std::string& path) {
  const auto ext = p.extensions.find("KHR_draco_mesh_compression");
  if (ext == p.extensions.end()) return nullptr;
  const tinygltf::Value& x = ext->second;
  const int view = x.Has("bufferView") && x.Get("bufferView").IsNumber() ? x.Get("bufferView").GetNumberAsInt() : -1;
  if (view < 0 || size_t(view) >= m.bufferViews.size()) fail(path, "a Draco primitive's buffer view does not exist");
  const tinygltf::BufferView& v = m.bufferViews[size_t(view)];
  if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size() || v.byteOffset > m.buffers[size_t(v.buffer)].data.size() ||
      v.byteLength > m.buffers[size_t(v.buffer)].data.size() - v.byteOffset)
    fail(path, "a Draco primitive's buffer view reaches past its buffer");
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(m.buffers[size_t(v.buffer)].data.data() + v.byteOffset), v.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) fail(path, "a Draco-compressed primitive cannot be decoded: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  auto out = std::make_unique<DracoPrimitive>();
  const size_t points = mesh->num_points();
  if (x.Has("attributes") && x.Get("attributes").IsObject()) {
    // (Value::Keys is not in Debian's libtinygltf: the object's map, as the header has it.)
    for (const auto& [name, id] : x.Get("attributes").Get<tinygltf::Value::Object>()) {
      const draco::PointAttribute* a = id.IsNumber() && id.GetNumberAsInt() >= 0
                                           ? mesh->GetAttributeByUniqueId(uint32_t(id.GetNumberAsInt())) : nullptr;
      if (!a || a->num_components() < 1 || a->num_components() > 4)
        fail(path, "a Draco primitive's " + name.substr(0, 40) + " is not in its data");
      const int n = a->num_components();
      std::vector<float> values(points * size_t(n));
      for (size_t i = 0; i < points; ++i)
        if (!a->ConvertValue<float>(a->mapped_index(draco::PointIndex(uint32_t(i))), int8_t(n), &values[i * size_t(n)]))
          fail(path, "a Draco primitive's " + name.substr(0, 40) + " cannot be read as numbers");
      out->attributes[name] = std::make_shared<Accessor>(std::move(values), n, path);
    }
  }
  if (mesh->num_faces() > 0) {
    std::vector<uint32_t> corners;
    corners.reserve(size_t(mesh->num_faces()) * 3);
    for (uint32_t f = 0; f < mesh->num_faces(); ++f)
      for (int k = 0; k < 3; ++k) corners.push_back(mesh->face(draco::FaceIndex(f))[k].value());
    out->indices = std::make_shared<Accessor>(corners, path);
  }
  return out;
}

}  // namespace mvr::gltf
