#pragma once
// A glTF 2.0 document built in code, for loader tests and scene fixtures:
// one buffer (a data URI) that accessors are appended to.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace mvr::test {

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += abc[n >> 18 & 63];
    out += abc[n >> 12 & 63];
    out += i + 1 < bytes.size() ? abc[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? abc[n & 63] : '=';
  }
  return out;
}

// A glTF document with one buffer (a data URI) that accessors are appended
// to, each in a buffer view of its own.
struct Document {
  using Json = nlohmann::json;
  Json json = {{"asset", {{"version", "2.0"}}}, {"buffers", Json::array()}, {"bufferViews", Json::array()},
               {"accessors", Json::array()}};
  std::vector<unsigned char> bytes;

  template <class T>
  int accessor(const std::vector<T>& values, int componentType, const char* type, size_t count) {
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t at = bytes.size();
    bytes.resize(at + values.size() * sizeof(T));
    std::memcpy(bytes.data() + at, values.data(), values.size() * sizeof(T));
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", values.size() * sizeof(T)}});
    json["accessors"].push_back({{"bufferView", json["bufferViews"].size() - 1},
                                 {"componentType", componentType},
                                 {"type", type},
                                 {"count", count}});
    return int(json["accessors"].size()) - 1;
  }
  int positions(const std::vector<float>& xyz) { return accessor(xyz, 5126, "VEC3", xyz.size() / 3); }
  std::string write(const std::filesystem::path& path) {
    if (!bytes.empty())
      json["buffers"] = Json::array({{{"byteLength", bytes.size()},
                                      {"uri", "data:application/octet-stream;base64," + base64(bytes)}}});
    std::ofstream(path) << json.dump();
    return path.string();
  }
};

}  // namespace mvr::test
