// glTF 2.0 files the tests write (mvr/assets/gltf_io.h): the node hierarchy
// and instancing, primitive modes and index types, flat normals where a
// file has none, materials and their mapping, vertex colours, a texture
// whose texels come through, and bad files as one-line errors.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/file_camera.h"
#include "mvr/image.h"
#include "mvr/images/image_file.h"
#include "mvr/assets/mesh_io.h"
#include "mvr/assets/scene_io.h"
#include "shading/lighting.h"
#include "tests/support/file_test.h"
#include "tests/support/gltf_document.h"
#include "tests/support/render_helpers.h"
#include "tests/support/solid_png.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using test::Document;
using test::kRed;
using test::writeRedPng;

class Gltf : public test::FileTest {};

// One triangle in z = 0; mesh 0 draws it.
Document triangleDocument() {
  Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", p}}}}})}}});
  return d;
}

TEST_F(Gltf, HierarchyInstancingAndFlatNormals) {
  Document d = triangleDocument();
  // Node 0 (translated) has child 1 (scaled, draws mesh 0); node 2 draws
  // mesh 0 by a matrix. Only the default scene's nodes count: scene 0
  // would add node 3 too.
  d.json["nodes"] = Json::array({{{"translation", {10, 0, 0}}, {"children", {1}}},
                                 {{"scale", {2, 2, 2}}, {"mesh", 0}},
                                 {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}, {"mesh", 0}},
                                 {{"mesh", 0}}});
  d.json["scenes"] = Json::array({{{"nodes", {0, 1, 2, 3}}}, {{"nodes", {0, 2}}}});
  d.json["scene"] = 1;
  const Scene s = loadMesh(d.write(dir_ / "tree.gltf"));
  ASSERT_EQ(s.triangles.size(), 2u);
  // Instance 1: T(10,0,0) S(2); instance 2: z + 5.
  EXPECT_EQ(s.positions[s.triangles[0].y], glm::vec3(12, 0, 0));
  EXPECT_EQ(s.positions[s.triangles[0].z], glm::vec3(10, 2, 0));
  EXPECT_EQ(s.positions[s.triangles[1].y], glm::vec3(1, 0, 5));
  for (const glm::vec3& n : s.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // flat, counter-clockwise
  EXPECT_TRUE(s.uvs.empty());
  EXPECT_TRUE(s.warnings.empty());
}

TEST_F(Gltf, StripFanIndexTypesAndMirroring) {
  Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  const int n = d.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3", 4);
  const int strip = d.accessor(std::vector<uint8_t>{0, 1, 2, 3}, 5121, "SCALAR", 4);
  const int fan = d.accessor(std::vector<uint16_t>{0, 1, 3, 2}, 5123, "SCALAR", 4);
  const int lines = d.accessor(std::vector<uint32_t>{0, 1}, 5125, "SCALAR", 2);
  const Json attributes = {{"POSITION", p}, {"NORMAL", n}};
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", attributes}, {"indices", strip}, {"mode", 5}},
                                                               {{"attributes", attributes}, {"indices", fan}, {"mode", 6}},
                                                               {{"attributes", attributes}, {"indices", lines}, {"mode", 1}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}, {{"mesh", 0}, {"scale", {-1, 1, 1}}}});
  d.json["scenes"] = Json::array({{{"nodes", {0, 1}}}});
  const Scene s = loadMesh(d.write(dir_ / "modes.gltf"));
  // 2 + 2 per instance, then the line of each as a prism of 8 after them.
  ASSERT_EQ(s.triangles.size(), 8u + 2 * 8);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("points and lines drawn as small solids"), std::string::npos);
  // Every triangle faces its normal: counter-clockwise seen from +z, also
  // in the mirrored instance (its winding flipped, its normals kept +z).
  for (size_t i = 0; i < 8; ++i) {
    const glm::uvec3 t = s.triangles[i];
    const glm::vec3 a = s.positions[t.x], b = s.positions[t.y], c = s.positions[t.z];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
    EXPECT_EQ(s.normals[t.x], glm::vec3(0, 0, 1));
  }
}

TEST_F(Gltf, MaterialsVertexColoursAndTexture) {
  Document d;
  const int p = d.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  const int uv = d.accessor(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, 5126, "VEC2", 4);
  const int colour = d.accessor(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255},
                                5121, "VEC4", 4);
  d.json["accessors"][size_t(colour)]["normalized"] = true;
  const int idx = d.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 6);
  writeRedPng(dir_ / "red.png", 4);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  d.json["materials"] = Json::array(
      {{{"name", "shiny"},
        {"doubleSided", true},
        {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}},
        {"emissiveFactor", {0.4, 0.2, 0.1}},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2}}}}}},
       {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
        {"emissiveFactor", {1, 0.5, 1}},
        {"emissiveTexture", {{"index", 0}}}}});
  d.json["meshes"] = Json::array(
      {{{"primitives", Json::array({{{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}, {"COLOR_0", colour}}},
                                     {"indices", idx},
                                     {"material", 0}},
                                    {{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}, {"indices", idx}, {"material", 1}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const Scene s = loadMesh(d.write(dir_ / "materials.gltf"));
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& shiny = s.materials[0];
  EXPECT_EQ(shiny.name, "shiny");
  EXPECT_EQ(shiny.diffuse, glm::vec3(0.5f, 0.25f, 1.0f));  // metallic 0: all of the base is diffuse
  EXPECT_EQ(shiny.specular, glm::vec3(0.04f));  // F0 of glTF's dielectric (ior 1.5)
  EXPECT_EQ(shiny.specularModel, SpecularModel::Ggx);
  EXPECT_EQ(shiny.roughness, 0.5f);
  EXPECT_TRUE(shiny.twoSided);
  EXPECT_NEAR(glm::distance(shiny.emission, glm::vec3(0.8f, 0.4f, 0.2f)), 0.0f, 1e-6f);  // times the strength
  // The defaults (metallic 1, roughness 1): a rough metal, no diffuse
  // part, its F0 the base colour tinted by the texture's mean (red.png's
  // texels); single-sided.
  const Material& textured = s.materials[1];
  EXPECT_EQ(textured.diffuse, glm::vec3(0.0f));
  EXPECT_EQ(textured.roughness, 1.0f);
  EXPECT_GT(textured.specular.r, textured.specular.g);
  EXPECT_GT(textured.specular.g, 0.0f);
  EXPECT_FALSE(textured.twoSided);
  ASSERT_TRUE(textured.textureImage);
  EXPECT_EQ(textured.textureImage->width, 4);
  EXPECT_EQ(textured.textureImage->pixel(1, 2), glm::vec4(200, 40, 20, 255) / 255.0f);
  // emissiveTexture on the base colour's coordinates: per texel, the
  // factor kept to scale them.
  EXPECT_EQ(textured.emission, glm::vec3(1, 0.5f, 1));
  ASSERT_TRUE(textured.emissionImage);
  EXPECT_EQ(textured.emissionImage->pixel(1, 2), glm::vec4(200, 40, 20, 255) / 255.0f);
  EXPECT_EQ(textured.emissionTexture, textured.texture);
  EXPECT_TRUE(shiny.emissionTexture.empty());
  EXPECT_TRUE(std::none_of(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
    return w.find("emissiveTexture") != std::string::npos;
  })) << ::testing::PrintToString(s.warnings);
  // Vertex colours and uv (v flipped: glTF's runs down the image); no
  // normals, so flat ones, each triangle its own three corners.
  ASSERT_EQ(s.colors.size(), 12u);
  EXPECT_EQ(s.colors[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(s.colors[6], glm::vec3(1, 1, 1));  // none given
  EXPECT_EQ(s.uvs[0], glm::vec2(0, 0));
  EXPECT_EQ(s.uvs[2], glm::vec2(1, 1));
}

// An emissiveTexture on other coordinates than the base colour's (here
// TEXCOORD_1) would need a second set per vertex: it is drawn as its mean
// colour (linear) times the factor, said once. Without a base colour
// texture, the emission's own coordinates are the ones the vertices carry.
TEST_F(Gltf, EmissionOnOtherCoordinatesIsItsMean) {
  Document d;
  const int p = d.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0});
  const int uv = d.accessor(std::vector<float>{0, 1, 1, 1, 1, 0}, 5126, "VEC2", 3);
  writeRedPng(dir_ / "red.png", 4);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  d.json["materials"] = Json::array(
      {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
        {"emissiveFactor", {1, 0.5, 1}},
        {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}},
       {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}, {"texCoord", 1}}}}});
  const Json attributes = {{"POSITION", p}, {"TEXCOORD_0", uv}, {"TEXCOORD_1", uv}};
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", attributes}, {"material", 0}},
                                                               {{"attributes", attributes}, {"material", 1}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const Scene s = loadMesh(d.write(dir_ / "emission.gltf"));
  ASSERT_EQ(s.materials.size(), 2u);
  const glm::vec3 mean(linearOfSrgb8(200), linearOfSrgb8(40), linearOfSrgb8(20));
  EXPECT_NEAR(glm::distance(s.materials[0].emission, mean * glm::vec3(1, 0.5f, 1)), 0.0f, 1e-5f);
  EXPECT_TRUE(s.materials[0].emissionTexture.empty());
  EXPECT_EQ(std::count_if(s.warnings.begin(), s.warnings.end(), [](const std::string& w) {
              return w.find("emissiveTexture on other coordinates than baseColorTexture drawn as its mean colour") !=
                     std::string::npos;
            }), 1) << ::testing::PrintToString(s.warnings);
  EXPECT_FALSE(s.materials[1].emissionTexture.empty());  // its own TEXCOORD_1
  EXPECT_EQ(s.materials[1].emission, glm::vec3(1.0f));
}

// A quad textured by a glTF image (external PNG, one colour), lit head
// on: svr's and mvr's views show the texture's colour, and agree.
TEST_F(Gltf, TexturedQuadMvrAgainstSvr) {
  test::sharedContext();
  Document d;
  const int p = d.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  const int n = d.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3", 4);
  const int uv = d.accessor(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, 5126, "VEC2", 4);
  const int idx = d.accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, 5121, "SCALAR", 6);
  writeRedPng(dir_ / "red.png", 8);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  d.json["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0}}}}});
  d.json["meshes"] = Json::array(
      {{{"primitives", Json::array({{{"attributes", {{"POSITION", p}, {"NORMAL", n}, {"TEXCOORD_0", uv}}},
                                     {"indices", idx},
                                     {"material", 0}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  Scene scene = loadScene(d.write(dir_ / "quad.gltf"));
  scene.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  scene.ambient = glm::vec3(0.0f);
  const ShearingCamera cam(cameraFor(scene, 64, 48), 64, 48, 5);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  auto mvr = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink a = test::renderViews(*svr, cam), b = test::renderViews(*mvr, cam);
  const Image& centre = a.views.at({0, 2});
  // The middle pixel: texel colour (200, 40, 20) sRGB, lit by 1 head on.
  const glm::vec4 c = centre.linear(32, 24);
  EXPECT_NEAR(c.r, decodeSrgb8(kRed).r, 0.02f);
  EXPECT_GT(c.r, 5 * c.g);
  test::expectCloseOnAnyGl(test::compareViews(a, b), 0.99, 30.0, "glTF textured quad, mvr cpu");
}

// KHR_texture_transform: the extension's own example (the lower-left
// quadrant, turned a quarter clockwise) on three corners, worked by hand.
TEST_F(Gltf, TextureTransformAsTheExtensionDefines) {
  Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int uv = d.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
  writeRedPng(dir_ / "red.png", 2);
  d.json["images"] = Json::array({{{"uri", "red.png"}}});
  d.json["textures"] = Json::array({{{"source", 0}}});
  const Json transform = {{"offset", {0, 1}}, {"rotation", 1.57079632679}, {"scale", {0.5, 0.5}}};
  d.json["materials"] = Json::array(
      {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}});
  d.json["meshes"] = Json::array(
      {{{"primitives", Json::array({{{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}, {"material", 0}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  const Scene s = loadMesh(d.write(dir_ / "transform.gltf"));
  // glTF (u, v) -> S R T -> (0, 1), (0, 0.5), (0.5, 1); ours flip v.
  const glm::vec2 expected[3] = {{0, 0}, {0, 0.5}, {0.5, 0}};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(s.uvs[s.triangles[0][k]].x, expected[k].x, 1e-6) << k;
    EXPECT_NEAR(s.uvs[s.triangles[0][k]].y, expected[k].y, 1e-6) << k;
  }
}

// KHR_lights_punctual: a directional light of 3 lux turned to shine down,
// and a point light of 100 cd 10 away from the triangle's centre (1 lux
// there): 3/4 and 1/4 of the exposure. A bare file keeps its lights,
// moved with the mesh as it is centred.
// KHR_lights_punctual in physical units: a 3 lux sun is 3 / pi, a
// 100 cd bulb 100 / pi at distance 1, falling off as 1/d^2 (1 lux at the
// triangle, 10 away). --exposure auto brings the sum at the centre to 1
// (3 : 1), as before physical units; an EV of 1 doubles every light.
TEST_F(Gltf, PunctualLightsAreInPhysicalUnits) {
  Document d = triangleDocument();
  d.json["extensionsUsed"] = {"KHR_lights_punctual"};
  d.json["extensions"] = {{"KHR_lights_punctual",
                           {{"lights", Json::array({{{"type", "directional"}, {"intensity", 3}},
                                                    {{"type", "point"}, {"intensity", 100}, {"color", {1, 0.5, 0}},
                                                     {"range", 20}}})}}}};
  const Json sun = {{"KHR_lights_punctual", {{"light", 0}}}}, bulb = {{"KHR_lights_punctual", {{"light", 1}}}};
  d.json["nodes"] = Json::array({{{"mesh", 0}},
                                 {{"rotation", {-0.70710678, 0, 0, 0.70710678}}, {"extensions", sun}},
                                 {{"translation", {0.5, 0.5, 10}}, {"extensions", bulb}}});
  const std::string path = d.write(dir_ / "lights.gltf");
  const Scene s = loadMesh(path);
  ASSERT_EQ(s.lights.size(), 2u);
  const float pi = float(M_PI);
  EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
  EXPECT_FALSE(s.lights[0].falloff);
  EXPECT_NEAR(glm::distance(s.lights[0].vector, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(s.lights[0].color, glm::vec3(3.0f / pi)), 0.0f, 1e-6f);
  EXPECT_EQ(s.lights[1].type, Light::Type::Point);
  EXPECT_TRUE(s.lights[1].falloff);
  EXPECT_EQ(s.lights[1].range, 20.0f);
  EXPECT_NEAR(glm::distance(s.lights[1].color, glm::vec3(100.0f, 50.0f, 0.0f) / pi), 0.0f, 1e-4f);
  // The range window at d = 10 of 20: 1 - (1/2)^4 = 15/16, over d^2 = 100.
  const glm::vec3 centre(0.5f, 0.5f, 0.0f);
  EXPECT_NEAR(distanceFalloff(s.lights[1], centre), 15.0f / 16.0f / 100.0f, 1e-7f);
  EXPECT_EQ(distanceFalloff(s.lights[1], glm::vec3(0.5f, 0.5f, -10.0f)), 0.0f);  // at the range
  for (const Light& l : s.lights) EXPECT_NEAR(l.autoExposure, pi / (3.0f + 100.0f * 15.0f / 16.0f / 100.0f), 1e-6f);
  Scene automatic = s;
  shading::applyExposure(automatic, std::nullopt);
  EXPECT_NEAR(automatic.lights[0].color.r + automatic.lights[1].color.r * distanceFalloff(automatic.lights[1], centre),
              1.0f, 1e-5f);
  EXPECT_EQ(automatic.ambient, s.ambient);
  Scene exposed = s;
  shading::applyExposure(exposed, 1.0f);
  EXPECT_NEAR(exposed.lights[0].color.r, 6.0f / pi, 1e-6f);
  EXPECT_EQ(exposed.ambient, 2.0f * s.ambient);
  const Scene centred = loadScene(path);
  ASSERT_EQ(centred.lights.size(), 2u);
  EXPECT_NEAR(glm::distance(centred.lights[1].vector, glm::vec3(0, 0, 10)), 0.0f, 1e-6f);
  // In a scene file that names no lights the file's lights keep their
  // own exposure.
  std::ofstream(dir_ / "lights.json") << R"({"meshes": [{"file": "lights.gltf"}]})";
  Scene framed = loadScene((dir_ / "lights.json").string());
  ASSERT_EQ(framed.lights.size(), 2u);
  shading::applyExposure(framed, std::nullopt);
  EXPECT_NEAR(framed.lights[0].color.r, automatic.lights[0].color.r, 1e-6f);
}

// A spot light keeps its cone, its axis down its node's -z (here turned to
// shine along -y) and is exposed as a point light at its place.
TEST_F(Gltf, SpotLightsKeepTheirCones) {
  Document d = triangleDocument();
  d.json["extensionsUsed"] = {"KHR_lights_punctual"};
  d.json["extensions"] = {{"KHR_lights_punctual",
                           {{"lights", Json::array({{{"type", "spot"}, {"intensity", 10},
                                                     {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.4}}}},
                                                    {{"type", "spot"}, {"intensity", 10}, {"spot", Json::object()}}})}}}};
  d.json["nodes"] = Json::array({{{"mesh", 0}},
                                 {{"rotation", {-0.70710678, 0, 0, 0.70710678}}, {"translation", {0, 5, 0}},
                                  {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                                 {{"translation", {0, 0, 50}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}}});
  const Scene s = loadMesh(d.write(dir_ / "spot.gltf"));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Spot);
  EXPECT_NEAR(glm::distance(s.lights[0].vector, glm::vec3(0, 5, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(s.lights[0].axis, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(s.lights[0].cosInner, std::cos(0.2f));
  EXPECT_FLOAT_EQ(s.lights[0].cosOuter, std::cos(0.4f));
  // The defaults, 0 and pi/4; and the near spot has most of the exposure.
  EXPECT_FLOAT_EQ(s.lights[1].cosInner, 1.0f);
  EXPECT_NEAR(s.lights[1].cosOuter, std::cos(0.7853981634f), 1e-6f);
  EXPECT_GT(s.lights[0].color.x, 0.9f);
}

// A file camera as the centre view: the scene in the camera's frame, the
// image plane through the scene's centre, the plane's height from yfov.
TEST_F(Gltf, FileCameraBecomesTheCentreView) {
  Document d = triangleDocument();
  d.json["cameras"] = Json::array({{{"type", "perspective"}, {"name", "front"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}},
                                   {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}});
  // "front" 4 in front of the triangle's centre; camera 1 on +x, turned
  // a quarter about y to look down -x.
  d.json["nodes"] = Json::array({{{"mesh", 0}},
                                 {{"translation", {0.5, 0.5, 4}}, {"camera", 0}},
                                 {{"translation", {4.5, 0.5, 0}}, {"rotation", {0, 0.70710678, 0, 0.70710678}}, {"camera", 1}}});
  const std::string path = d.write(dir_ / "cameras.gltf");
  Scene front = loadMesh(path);
  ASSERT_EQ(front.fileCameras.size(), 2u);
  const CameraSpec spec = viewThrough(front, "front", 200, 100);
  EXPECT_NEAR(spec.distance, 4.0, 1e-6);
  EXPECT_NEAR(spec.planeHeight, 8.0 * std::tan(0.25), 1e-6);
  EXPECT_NEAR(spec.planeWidth, 2.0 * spec.planeHeight, 1e-6);
  EXPECT_NEAR(glm::distance(front.positions[0], glm::vec3(-0.5f, -0.5f, 0.0f)), 0.0f, 1e-6f);
  ASSERT_TRUE(front.camera);
  Scene side = loadMesh(path);
  viewThrough(side, "1", 100, 100);
  EXPECT_NEAR(glm::distance(side.positions[0], glm::vec3(0.0f, -0.5f, -0.5f)), 0.0f, 1e-5f);
  // The triangle's +z is the camera's -x: it is seen edge on.
  for (const glm::vec3& n : side.normals) EXPECT_NEAR(glm::distance(n, glm::vec3(-1, 0, 0)), 0.0f, 1e-5f);
  for (const auto& [which, message] : {std::pair<std::string, std::string>{"back", "'back' is neither a camera of"},
                                       {"2", "nor an index below 2"}}) {
    Scene s = loadMesh(path);
    test::expectOneLineError([&] { viewThrough(s, which, 100, 100); }, "--camera", message);
  }
}

// glTF 1.0 (its objects keyed by name; the version a string or, as old
// exporters wrote, a number): read by assimp, with a warning saying so.
TEST_F(Gltf, VersionOneIsReadByAssimp) {
  std::vector<unsigned char> bytes(42, 0);
  const float corners[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t indices[3] = {0, 1, 2};
  std::memcpy(bytes.data(), corners, 36);
  std::memcpy(bytes.data() + 36, indices, 6);
  Json one = {{"scene", "s"}, {"scenes", {{"s", {{"nodes", {"n"}}}}}}, {"nodes", {{"n", {{"meshes", {"m"}}}}}},
              {"meshes", {{"m", {{"primitives", Json::array({{{"attributes", {{"POSITION", "p"}}}, {"indices", "i"}, {"mode", 4}}})}}}}},
              {"accessors", {{"p", {{"bufferView", "v0"}, {"byteOffset", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}},
                             {"i", {{"bufferView", "v1"}, {"byteOffset", 0}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}}},
              {"bufferViews", {{"v0", {{"buffer", "b"}, {"byteOffset", 0}, {"byteLength", 36}, {"target", 34962}}},
                               {"v1", {{"buffer", "b"}, {"byteOffset", 36}, {"byteLength", 6}, {"target", 34963}}}}},
              {"buffers", {{"b", {{"byteLength", 42}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}}}};
  for (const Json& version : {Json("1.0"), Json(1)}) {
    one["asset"] = {{"version", version}};
    std::ofstream(dir_ / "one.gltf") << one.dump();
    const Scene s = loadMesh((dir_ / "one.gltf").string());
    ASSERT_EQ(s.triangles.size(), 1u) << version;
    EXPECT_EQ(s.positions[s.triangles[0].y], glm::vec3(1, 0, 0));
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings.back().find("glTF 1.0, read by assimp"), std::string::npos) << s.warnings.back();
  }
}

TEST_F(Gltf, BadFilesAreOneLineErrors) {
  auto expectError = [&](const std::string& path, const std::string& what) {
    test::expectOneLineError([&] { loadScene(path); }, fs::path(path).filename().string(), what);
  };
  expectError((dir_ / "none.glb").string(), "no such glTF file");
  std::ofstream(dir_ / "text.gltf") << "not json";
  expectError((dir_ / "text.gltf").string(), "");
  Document cycle = triangleDocument();
  cycle.json["nodes"] = Json::array({{{"mesh", 0}, {"children", {1}}}, {{"children", {0}}}});
  cycle.json["scenes"] = Json::array({{{"nodes", {0}}}});
  expectError(cycle.write(dir_ / "cycle.gltf"), "node 0 is its own ancestor");
  Document index = triangleDocument();
  const int far = index.accessor(std::vector<uint16_t>{0, 1, 7}, 5123, "SCALAR", 3);
  index.json["meshes"][0]["primitives"][0]["indices"] = far;
  index.json["nodes"] = Json::array({{{"mesh", 0}}});
  expectError(index.write(dir_ / "index.gltf"), "index 7 beyond the vertices");
  Document past = triangleDocument();
  past.json["accessors"][0]["count"] = 1000;
  past.json["nodes"] = Json::array({{{"mesh", 0}}});
  expectError(past.write(dir_ / "past.gltf"), "");
  // An infinity under a node's matrix is named as the file holds it (the
  // matrix would make NaNs of it; BoxWithInfinites.glb of assimp's files).
  Document infinite;
  infinite.positions({-INFINITY, -0.5f, 0.5f, 1, 0, 0, 0, 1, 0});
  infinite.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", 0}}}}})}}});
  infinite.json["nodes"] = Json::array({{{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1}}}});
  expectError(infinite.write(dir_ / "infinite.gltf"), "POSITION accessor 0 element 0 (-inf, -0.5, 0.5)");
  Document empty;
  empty.json["nodes"] = Json::array({{{"name", "nothing"}}});
  expectError(empty.write(dir_ / "empty.gltf"), "glTF scene has no triangles: it has no meshes");
  // "primitives" not an array (assimp's badArray.gltf) reads as none.
  Document notArray = triangleDocument();
  notArray.json["meshes"][0]["primitives"] = {{"attributes", {{"POSITION", 0}}}};
  notArray.json["nodes"] = Json::array({{{"mesh", 0}}});
  expectError(notArray.write(dir_ / "not_array.gltf"), "its meshes have no primitives array");
  // A GLB of version 1 goes to assimp, which names its fault; a
  // compressed mesh says so.
  std::ofstream(dir_ / "one.glb", std::ios::binary) << std::string("glTF\x01\0\0\0\x14\0\0\0", 12) << "12345678";
  expectError((dir_ / "one.glb").string(), "");
  // A GLB shorter than its header says (BoxTextured.glb of assimp's test files).
  std::ofstream(dir_ / "cut.glb", std::ios::binary) << std::string("glTF\x02\0\0\0\x40\0\0\0", 12) << "12345678";
  expectError((dir_ / "cut.glb").string(), "GLB is cut: its header says 64 bytes, the file has 20");
  Document meshopt = triangleDocument();
  meshopt.json["extensionsRequired"] = {"EXT_meshopt_compression"};
  meshopt.json["extensionsUsed"] = {"EXT_meshopt_compression"};
  meshopt.json["nodes"] = Json::array({{{"mesh", 0}}});
  expectError(meshopt.write(dir_ / "meshopt.gltf"), "needs the extension EXT_meshopt_compression");
}

}  // namespace
}  // namespace mvr
