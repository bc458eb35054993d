#pragma once
// A GLB as the fixture makers write one: one binary buffer that accessors
// are appended to, each in its own view, and the JSON beside it.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr::app {

struct Glb {
  using Json = nlohmann::json;
  explicit Glb(const std::string& generator)
      : json{{"asset", {{"version", "2.0"}, {"generator", generator}}},
             {"bufferViews", Json::array()},
             {"accessors", Json::array()}} {}

  Json json;
  std::vector<unsigned char> bin;

  template <class T>
  int accessor(const std::vector<T>& values, int componentType, const char* type, size_t count) {
    return accessorOfView(view(values.data(), values.size() * sizeof(T)), componentType, type, count);
  }
  int accessorOfView(int view, int componentType, const char* type, size_t count) {
    json["accessors"].push_back({{"bufferView", view}, {"componentType", componentType}, {"type", type}, {"count", count}});
    return int(json["accessors"].size()) - 1;
  }
  // Bytes in a view of their own (an image's, say).
  int view(const void* data, size_t bytes) {
    while (bin.size() % 4) bin.push_back(0);
    const size_t at = bin.size();
    bin.resize(at + bytes);
    std::memcpy(bin.data() + at, data, bytes);
    json["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", bytes}});
    return int(json["bufferViews"].size()) - 1;
  }
  void write(const std::string& path) {
    while (bin.size() % 4) bin.push_back(0);
    json["buffers"] = Json::array({{{"byteLength", bin.size()}}});
    std::string text = json.dump();
    while (text.size() % 4) text += ' ';
    auto word = [](uint32_t w) { return std::string(reinterpret_cast<const char*>(&w), 4); };
    std::ofstream out(path, std::ios::binary);
    out << "glTF" << word(2) << word(uint32_t(28 + text.size() + bin.size())) << word(uint32_t(text.size())) << "JSON"
        << text << word(uint32_t(bin.size())) << std::string("BIN\0", 4);
    out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    if (!out.flush()) fail(path, "cannot write");
  }
};

}  // namespace mvr::app
