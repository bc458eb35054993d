#pragma once
// A scene file whose meshes are a glTF and an OBJ with its MTL, written by
// the tests: what a user brings from their tools, in small. The glTF holds
// a textured, glossy quad (an 8 x 8 texture; metallic 0, roughness 0.5:
// a highlight) and a tetrahedron without normals, with vertex colours,
// drawn twice through a node hierarchy; the OBJ a quad textured by a
// 4 x 4 map_Kd (another size: another GL texture group) and a triangle of
// a Kd-only material. The glossy quad and the triangle give off light
// (emissiveFactor, Ke). Two lights, one of them a point light.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mvr/image.h"
#include "mvr/images/image_file.h"
#include "tests/support/gltf_document.h"
#include "tests/support/solid_png.h"

namespace mvr::test {

inline std::string writeAssetScene(const std::filesystem::path& dir) {
  using Json = nlohmann::json;
  std::filesystem::create_directories(dir);
  writeRedPng(dir / "red.png", 8);
  Image blue(4, 4, PixelType::Srgb8);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) blue.setLinear(x, y, (x + y) % 2 ? glm::vec4(0.1f, 0.2f, 0.9f, 1) : glm::vec4(0.6f, 0.7f, 1, 1));
  writeImage(blue, (dir / "blue.png").string());

  Document d;
  const int quad = d.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  const int normals = d.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3", 4);
  const int uv = d.accessor(std::vector<float>{0, 2, 2, 2, 2, 0, 0, 0}, 5126, "VEC2", 4);
  const int quadIdx = d.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 6);
  const int tetra = d.positions({0, 0, 0.6f, 0.5f, -0.4f, 0, -0.5f, -0.4f, 0, 0, 0.5f, 0});
  const int colours = d.accessor(std::vector<float>{1, 1, 1, 1, 0.3f, 0.3f, 0.3f, 1, 0.3f, 1, 0.3f, 0.3f, 1, 0.3f}, 5126, "VEC3", 4);
  const int tetraIdx = d.accessor(std::vector<uint8_t>{0, 1, 3, 0, 2, 1, 0, 3, 2, 1, 2, 3}, 5121, "SCALAR", 12);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  d.json["materials"] = Json::array(
      {{{"name", "glossy"},
        {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}},
        {"emissiveFactor", {0.1, 0.2, 0.3}}},
       {{"name", "green"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.3, 0.9, 0.4, 1}}}}}});
  d.json["meshes"] = Json::array(
      {{{"primitives", Json::array({{{"attributes", {{"POSITION", quad}, {"NORMAL", normals}, {"TEXCOORD_0", uv}}},
                                     {"indices", quadIdx},
                                     {"material", 0}}})}},
       {{"primitives", Json::array({{{"attributes", {{"POSITION", tetra}, {"COLOR_0", colours}}},
                                     {"indices", tetraIdx},
                                     {"material", 1}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}},
                                 {{"translation", {0.5, 0.3, 0.4}}, {"children", {2}}},
                                 {{"scale", {0.8, 0.8, 0.8}}, {"mesh", 1}},
                                 {{"translation", {-0.4, -0.5, 0.3}}, {"rotation", {0, 0.38268343, 0, 0.92387953}}, {"mesh", 1}}});
  d.json["scenes"] = Json::array({{{"nodes", {0, 1, 3}}}});
  d.write(dir / "parts.gltf");

  std::ofstream(dir / "parts.mtl") << "newmtl checker\nKd 1 1 1\nKs 0 0 0\nmap_Kd blue.png\n"
                                      "newmtl yellow\nKd 0.9 0.8 0.2\nKs 0 0 0\nKe 0 0.1 0.3\n";
  std::ofstream(dir / "parts.obj") << "mtllib parts.mtl\n"
                                      "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 0.8\n"
                                      "vt 0 0\nvt 3 0\nvt 3 3\nvt 0 3\nvn 0 0 1\n"
                                      "usemtl checker\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
                                      "usemtl yellow\nf 1 2 5\n";
  const std::string scene = (dir / "assets.json").string();
  std::ofstream(scene) << R"({"meshes": [
    {"file": "parts.gltf", "transform": {"translate": [-1.1, 0, 0], "scale": 0.9}},
    {"file": "parts.obj", "transform": {"translate": [1.1, 0, -0.3], "rotate": [-25, 0, 1, 0], "scale": 0.9}}],
  "lights": [{"type": "directional", "direction": [-0.3, -0.4, -1], "color": [0.7, 0.7, 0.7]},
             {"type": "point", "position": [1, 2, 3], "color": [0.3, 0.3, 0.3]}]})";
  return scene;
}

}  // namespace mvr::test
