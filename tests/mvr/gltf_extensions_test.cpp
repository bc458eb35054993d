// The parts of glTF 2.0 past meshes and materials that real files use
// (issue 56): sparse accessors, every JOINTS_n / WEIGHTS_n set, the
// texture coordinate set a material names (and KHR_texture_transform's
// override of it), KHR_materials_unlit, Draco-compressed primitives, and
// a warning naming what is not read. Each on a file the test writes, checked against values by hand.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mvr/assets/mesh_io.h"
#include "mvr/scene_animation.h"
#include "mvr/scene_pose.h"
#include "tests/support/animated_gltf.h"
#include "tests/support/file_test.h"
#include "tests/support/gltf_document.h"
#include "tests/support/solid_png.h"

namespace mvr {
namespace {

using Json = nlohmann::json;
using test::Document;

class GltfExtensions : public test::FileTest {};

// Turns accessor `a` sparse: `indices` (uint16) get `values` (float VEC3).
void makeSparse(Document& d, int a, const std::vector<uint16_t>& indices, const std::vector<float>& values) {
  const int i = d.accessor(indices, 5123, "SCALAR", indices.size());
  const int v = d.accessor(values, 5126, "VEC3", values.size() / 3);
  d.json["accessors"][a]["sparse"] = {{"count", indices.size()},
                                      {"indices", {{"bufferView", d.json["accessors"][i]["bufferView"]}, {"componentType", 5123}}},
                                      {"values", {{"bufferView", d.json["accessors"][v]["bufferView"]}}}};
}

// A triangle whose third corner a sparse accessor moves from (0, 1, 0) to
// (0, 2, 0), and a morph target of zeros (no buffer view, as exporters
// write them) whose sparse value lifts its second corner by 1 in z.
TEST_F(GltfExtensions, SparseAccessorsPutTheirValuesIn) {
  Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  makeSparse(d, p, {2}, {0, 2, 0});
  d.json["accessors"].push_back({{"componentType", 5126}, {"type", "VEC3"}, {"count", 3}});
  const int lift = int(d.json["accessors"].size()) - 1;
  makeSparse(d, lift, {1}, {0, 0, 1});
  d.json["meshes"] = Json::array({{{"weights", {0.5}},
                                   {"primitives", Json::array({{{"attributes", {{"POSITION", p}}},
                                                                {"targets", Json::array({{{"POSITION", lift}}})}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const Scene s = loadMesh(d.write(dir_ / "sparse.gltf"));
  ASSERT_EQ(s.triangles.size(), 1u);
  const glm::uvec3 t = s.triangles[0];
  EXPECT_EQ(s.positions[t[0]], glm::vec3(0, 0, 0));
  EXPECT_EQ(s.positions[t[1]], glm::vec3(1, 0, 0.5f));  // lifted by weight 0.5
  EXPECT_EQ(s.positions[t[2]], glm::vec3(0, 2, 0));

  Json doc = Json::parse(std::ifstream(dir_ / "sparse.gltf"));
  doc["accessors"][p]["sparse"]["count"] = 4;  // more than the accessor's 3
  std::ofstream(dir_ / "bad.gltf") << doc.dump();
  const std::string bad = (dir_ / "bad.gltf").string();
  test::expectOneLineError([&] { loadMesh(bad); }, bad, "sparse accessor");
}

// The two-joint strip of writeSkinnedGltf with each vertex's influences
// split over JOINTS_0 (root) and JOINTS_1 (tip), and its weights doubled
// (exporters' unnormalised sums): posed, it is the one-set file posed.
TEST_F(GltfExtensions, EveryJointSetCountsNormalisedTogether) {
  const std::string one = test::writeSkinnedGltf(dir_ / "one.gltf", true);
  Json doc = Json::parse(std::ifstream(one));
  Document d;
  d.json = doc;
  d.json["buffers"] = Json::array();
  // The one-set weights by row: (root, tip) (1, 0), (0.5, 0.5), (0, 1); doubled.
  const float rows[3][2] = {{2, 0}, {1, 1}, {0, 2}};
  std::vector<float> w0, w1;
  std::vector<uint8_t> j0, j1;
  for (int v = 0; v < 6; ++v) {
    w0.insert(w0.end(), {rows[v / 2][0], 0, 0, 0}), w1.insert(w1.end(), {rows[v / 2][1], 0, 0, 0});
    j0.insert(j0.end(), {0, 0, 0, 0}), j1.insert(j1.end(), {1, 0, 0, 0});
  }
  // The new accessors go into a second buffer: the first keeps the file's own.
  d.bytes.clear();
  auto second = [&](int a) {
    d.json["bufferViews"][d.json["accessors"][a]["bufferView"].get<int>()]["buffer"] = 1;
    return a;
  };
  auto& attributes = d.json["meshes"][0]["primitives"][0]["attributes"];
  attributes["JOINTS_0"] = second(d.accessor(j0, 5121, "VEC4", 6));
  attributes["WEIGHTS_0"] = second(d.accessor(w0, 5126, "VEC4", 6));
  attributes["JOINTS_1"] = second(d.accessor(j1, 5121, "VEC4", 6));
  attributes["WEIGHTS_1"] = second(d.accessor(w1, 5126, "VEC4", 6));
  d.json["buffers"] = Json::array({doc["buffers"][0], {{"byteLength", d.bytes.size()},
                                                       {"uri", "data:application/octet-stream;base64," + test::base64(d.bytes)}}});
  std::ofstream(dir_ / "two.gltf") << d.json.dump();
  Scene a = loadMesh(one), b = loadMesh((dir_ / "two.gltf").string());
  for (double t : {0.0, 1.0, 2.0}) {
    poseAnimations(a, t, "", glm::mat4(1.0f));
    poseAnimations(b, t, "", glm::mat4(1.0f));
    ASSERT_EQ(a.positions.size(), b.positions.size());
    for (size_t v = 0; v < a.positions.size(); ++v) {
      EXPECT_NEAR(glm::distance(a.positions[v], b.positions[v]), 0.0f, 1e-6f) << "t " << t << " vertex " << v;
      EXPECT_NEAR(glm::distance(a.normals[v], b.normals[v]), 0.0f, 1e-6f) << "t " << t << " vertex " << v;
    }
  }
}

// A textured triangle whose TEXCOORD_0 is all (0.9, 0.9) and TEXCOORD_1
// the corners: a base colour texture on texCoord 1 reads set 1; with
// KHR_texture_transform's texCoord 0 it reads set 0 again.
TEST_F(GltfExtensions, TextureReadsTheCoordinateSetItNames) {
  for (int override : {-1, 0}) {
    Document d;
    const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int uv0 = d.accessor(std::vector<float>{0.9f, 0.9f, 0.9f, 0.9f, 0.9f, 0.9f}, 5126, "VEC2", 3);
    const int uv1 = d.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    test::writeRedPng(dir_ / "red.png", 2);
    d.json["images"] = Json::array({{{"uri", "red.png"}}});
    d.json["textures"] = Json::array({{{"source", 0}}});
    Json texture = {{"index", 0}, {"texCoord", 1}};
    if (override >= 0) texture["extensions"] = {{"KHR_texture_transform", {{"texCoord", override}}}};
    d.json["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", texture}}}}});
    d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv0}, {"TEXCOORD_1", uv1}}},
                                                                  {"material", 0}}})}}});
    d.json["nodes"] = Json::array({{{"mesh", 0}}});
    const Scene s = loadMesh(d.write(dir_ / "sets.gltf"));
    const glm::vec2 expected[3] = {{0, 1}, {1, 1}, {0, 0}};  // set 1, v flipped
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 uv = s.uvs[s.triangles[0][k]];
      const glm::vec2 want = override == 0 ? glm::vec2(0.9f, 0.1f) : expected[k];
      EXPECT_NEAR(uv.x, want.x, 1e-6) << "override " << override << " corner " << k;
      EXPECT_NEAR(uv.y, want.y, 1e-6) << "override " << override << " corner " << k;
    }
  }
}

// KHR_materials_unlit: the base colour (times its texture) as it is,
// nothing lit, nothing given off; a file using an extension we do not
// read says so once, by name.
TEST_F(GltfExtensions, UnlitIsItsBaseColourAndUnreadExtensionsAreNamed) {
  Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int uv = d.accessor(std::vector<float>{0, 1, 1, 1, 1, 0}, 5126, "VEC2", 3);
  test::writeRedPng(dir_ / "red.png", 2);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  d.json["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_clearcoat"};
  const Json unlit = {{"KHR_materials_unlit", Json::object()}};
  d.json["materials"] = Json::array(
      {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.2}}},
        {"emissiveFactor", {1, 1, 1}},
        {"extensions", unlit}},
       {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}, {"extensions", unlit}}});
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", p}}}, {"material", 0}},
                                                               {{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}},
                                                                {"material", 1}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const Scene s = loadMesh(d.write(dir_ / "unlit.gltf"));
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& m = s.materials[0];
  EXPECT_TRUE(m.unlit);
  EXPECT_NEAR(glm::distance(m.diffuse, glm::vec3(0.2f, 0.4f, 0.6f)), 0.0f, 1e-6f);
  EXPECT_EQ(m.emission, glm::vec3(0.0f));
  EXPECT_EQ(m.specular, glm::vec3(0.0f));
  const Material& textured = s.materials[1];
  EXPECT_TRUE(textured.unlit);
  EXPECT_TRUE(textured.textureImage);
  EXPECT_EQ(textured.diffuse, glm::vec3(1.0f));
  EXPECT_EQ(textured.specular, glm::vec3(0.0f));
  int named = 0;
  for (const std::string& w : s.warnings) {
    EXPECT_EQ(w.find("KHR_materials_unlit"), std::string::npos) << w;
    named += w.find("KHR_materials_clearcoat") != std::string::npos;
  }
  EXPECT_EQ(named, 1);
}

// A quad of two triangles compressed by Draco's own encoder (positions
// unquantised, so exact), in a .gltf and in a .glb: the same corners.
TEST_F(GltfExtensions, DracoPrimitivesAreDecoded) {
  const float corners[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(2);
  const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (int f = 0; f < 2; ++f)
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(f), corners[f][0], corners[f][1], corners[f][2]);
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  ASSERT_TRUE(mesh);
  draco::Encoder encoder;
  draco::EncoderBuffer encoded;
  ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
  Document d;
  d.bytes.assign(encoded.data(), encoded.data() + encoded.size());
  d.json["bufferViews"].push_back({{"buffer", 0}, {"byteLength", encoded.size()}});
  d.json["accessors"] = Json::array({{{"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}},
                                     {{"componentType", 5126}, {"count", mesh->num_points()}, {"type", "VEC3"}}});
  const Json draco = {{"bufferView", 0}, {"attributes", {{"POSITION", mesh->attribute(position)->unique_id()}}}};
  d.json["extensionsUsed"] = d.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", 1}}}, {"indices", 0},
                                                                {"extensions", {{"KHR_draco_mesh_compression", draco}}}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const std::string gltf = d.write(dir_ / "draco.gltf");
  // The same as a GLB: header, JSON chunk (its buffer the binary chunk), binary chunk.
  Json glbJson = d.json;
  glbJson["buffers"] = Json::array({{{"byteLength", d.bytes.size()}}});
  std::string json = glbJson.dump(), bin(d.bytes.begin(), d.bytes.end());
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  auto word = [](uint32_t w) { return std::string(reinterpret_cast<const char*>(&w), 4); };
  std::ofstream(dir_ / "draco.glb", std::ios::binary)
      << "glTF" << word(2) << word(uint32_t(28 + json.size() + bin.size())) << word(uint32_t(json.size())) << "JSON" << json
      << word(uint32_t(bin.size())) << std::string("BIN\0", 4) << bin;
  // Draco may reorder faces and start a face at another corner; the
  // winding it keeps. Each face is one of the quad's, rotated.
  auto corner = [&](int f, int k) { return glm::vec3(corners[f][k][0], corners[f][k][1], corners[f][k][2]); };
  for (const std::string& path : {gltf, (dir_ / "draco.glb").string()}) {
    const Scene s = loadMesh(path);
    ASSERT_EQ(s.triangles.size(), 2u) << path;
    int found[2] = {0, 0};
    for (const glm::uvec3& t : s.triangles)
      for (int f = 0; f < 2; ++f)
        for (int r = 0; r < 3; ++r)
          found[f] += s.positions[t[0]] == corner(f, r) && s.positions[t[1]] == corner(f, (r + 1) % 3) &&
                      s.positions[t[2]] == corner(f, (r + 2) % 3);
    EXPECT_EQ(found[0], 1) << path;
    EXPECT_EQ(found[1], 1) << path;
  }
}

}  // namespace
}  // namespace mvr
