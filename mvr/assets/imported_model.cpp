#include "mvr/assets/imported_model.h"

#include <algorithm>
#include <cstring>
#include <ostream>

#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr {
namespace {

using Json = nlohmann::json;
constexpr char kMagic[8] = {'M', 'V', 'R', 'I', 'M', 'P', '1', '\n'};

template <class T>
void put(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}

Json vec(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// Reads arrays in order from the bytes after the header, each checked
// against what is left.
class Cursor {
 public:
  Cursor(const std::string& bytes, size_t at, const std::string& where) : bytes_(bytes), at_(at), where_(where) {}
  template <class T>
  void take(std::vector<T>& v, size_t count) {
    if (count > (bytes_.size() - at_) / sizeof(T)) fail(where_, "the importer's output is cut short");
    v.resize(count);
    if (count) std::memcpy(v.data(), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
  }
  template <class T>
  void takeVectors(std::vector<T>& v, size_t count) {
    std::vector<typename T::value_type> flat;
    take(flat, count * T::length());
    v.resize(count);
    if (count) std::memcpy(v.data(), flat.data(), flat.size() * sizeof(flat[0]));
  }

 private:
  const std::string& bytes_;
  size_t at_;
  const std::string& where_;
};

glm::vec3 color(const Json& j) {
  glm::vec3 c(0.0f);
  for (int k = 0; k < 3 && j.is_array() && size_t(k) < j.size(); ++k) c[k] = j[size_t(k)].is_number() ? j[size_t(k)].get<float>() : 0.0f;
  return c;
}

}  // namespace

void writeImportedModel(std::ostream& out, const ImportedModel& model) {
  const Scene& s = model.scene;
  Json header = {{"vertices", s.positions.size()},
                 {"triangles", s.triangles.size()},
                 {"uvs", !s.uvs.empty()},
                 {"dropped", s.droppedFaces},
                 {"warnings", s.warnings},
                 {"materials", Json::array()},
                 {"embedded", Json::array()}};
  for (const Material& m : s.materials)
    header["materials"].push_back({{"name", m.name},
                                   {"diffuse", vec(m.diffuse)},
                                   {"specular", vec(m.specular)},
                                   {"shininess", m.shininess},
                                   {"ggx", m.specularModel == SpecularModel::Ggx},
                                   {"roughness", m.roughness},
                                   {"f90", m.specularF90},
                                   {"texture", m.texture},
                                   {"two_sided", m.twoSided},
                                   {"emission", vec(m.emission)}});
  for (const EmbeddedImage& e : model.embedded)
    header["embedded"].push_back({{"hint", e.hint}, {"width", e.width}, {"height", e.height}, {"bytes", e.bytes.size()}});
  // Names from the file may be any bytes: invalid UTF-8 is replaced, not thrown on.
  const std::string text = header.dump(-1, ' ', false, Json::error_handler_t::replace);
  const uint64_t length = text.size();
  out.write(kMagic, sizeof kMagic);
  out.write(reinterpret_cast<const char*>(&length), sizeof length);
  out << text;
  put(out, s.positions), put(out, s.normals), put(out, s.colors), put(out, s.uvs);
  put(out, s.triangles), put(out, s.materialIds);
  for (const EmbeddedImage& e : model.embedded) put(out, e.bytes);
}

ImportedModel readImportedModel(const std::string& bytes, const std::string& where) {
  uint64_t length = 0;
  if (bytes.size() < sizeof kMagic + sizeof length || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    fail(where, "the importer wrote no model");
  std::memcpy(&length, bytes.data() + sizeof kMagic, sizeof length);
  const size_t start = sizeof kMagic + sizeof length;
  if (length > bytes.size() - start) fail(where, "the importer's output is cut short");
  const Json h = Json::parse(bytes.substr(start, length), nullptr, false);
  if (!h.is_object() || !h["vertices"].is_number_unsigned() || !h["triangles"].is_number_unsigned() ||
      !h["materials"].is_array() || !h["embedded"].is_array())
    fail(where, "the importer wrote a malformed model");
  ImportedModel model;
  Scene& s = model.scene;
  s.source = where;
  const size_t vertices = h["vertices"].get<size_t>(), triangles = h["triangles"].get<size_t>();
  Cursor in(bytes, start + length, where);
  in.takeVectors(s.positions, vertices), in.takeVectors(s.normals, vertices), in.takeVectors(s.colors, vertices);
  in.takeVectors(s.uvs, h.value("uvs", false) ? vertices : 0);
  in.takeVectors(s.triangles, triangles), in.take(s.materialIds, triangles);
  for (const Json& m : h["materials"]) {
    Material mat;
    mat.name = m.value("name", "");
    mat.diffuse = glm::clamp(color(m["diffuse"]), 0.0f, 1.0f);
    mat.specular = glm::clamp(color(m["specular"]), 0.0f, 1.0f);
    mat.shininess = m["shininess"].is_number() ? std::clamp(m["shininess"].get<float>(), 1.0f, 1e4f) : 32.0f;
    if (m.value("ggx", false)) {
      mat.specularModel = SpecularModel::Ggx;
      mat.roughness = m["roughness"].is_number() ? std::clamp(m["roughness"].get<float>(), 0.0f, 1.0f) : 1.0f;
      mat.specularF90 = m["f90"].is_number() ? std::clamp(m["f90"].get<float>(), 0.0f, 1.0f) : 1.0f;
    }
    mat.texture = m.value("texture", "");
    mat.twoSided = m.value("two_sided", true);
    if (m.contains("emission")) mat.emission = glm::clamp(color(m["emission"]), 0.0f, 1.0f);
    s.materials.push_back(mat);
  }
  for (const Json& e : h["embedded"]) {
    EmbeddedImage& image = model.embedded.emplace_back();
    image.hint = e.value("hint", "");
    image.width = e.value("width", 0), image.height = e.value("height", 0);
    in.take(image.bytes, e.value("bytes", size_t(0)));
  }
  for (const Json& w : h["warnings"])
    if (w.is_string()) s.warnings.push_back(w.get<std::string>());
  s.droppedFaces = h.value("dropped", size_t(0));
  for (const glm::uvec3& t : s.triangles)
    if (t.x >= vertices || t.y >= vertices || t.z >= vertices) fail(where, "a triangle names a vertex that does not exist");
  for (uint32_t m : s.materialIds)
    if (m >= s.materials.size()) fail(where, "a triangle names a material that does not exist");
  return model;
}

}  // namespace mvr
