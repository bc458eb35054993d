// FBX, Collada and 3DS through mvr-import in a child process
// (mvr/assets/assimp_import.h): a Collada file the test writes (a node's
// transform, two materials, a texture beside it), and the ways it fails,
// each one line: assimp's message, a crash, no importer, another format.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "mvr/error.h"
#include "mvr/assets/mesh_io.h"
#include "tests/support/file_test.h"
#include "tests/support/solid_png.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// A quad of two triangles at z = 0.5 (its node's translation): one
// textured by red.png (Phong, black specular), one of a Lambert colour.
const char* const kCollada = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_images><image id="img"><init_from>Textures\RED.png</init_from></image></library_images>
  <library_effects>
    <effect id="fx"><profile_COMMON>
      <newparam sid="surf"><surface type="2D"><init_from>img</init_from></surface></newparam>
      <newparam sid="samp"><sampler2D><source>surf</source></sampler2D></newparam>
      <technique sid="common"><phong><diffuse><texture texture="samp" texcoord="uv"/></diffuse>
        <specular><color>0.5 0.5 0.5 1</color></specular><shininess><float>40</float></shininess></phong></technique>
    </profile_COMMON></effect>
    <effect id="fx2"><profile_COMMON><technique sid="common"><lambert>
      <diffuse><color>0.2 0.4 0.6 1</color></diffuse></lambert></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="mat" name="redtex"><instance_effect url="#fx"/></material>
    <material id="mat2" name="blue"><instance_effect url="#fx2"/></material>
  </library_materials>
  <library_geometries><geometry id="geo"><mesh>
    <source id="pos"><float_array id="pa" count="12">-1 -1 0 1 -1 0 1 1 0 -1 1 0</float_array>
      <technique_common><accessor source="#pa" count="4" stride="3"><param name="X" type="float"/>
        <param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <source id="tc"><float_array id="ta" count="8">0 0 1 0 1 1 0 1</float_array>
      <technique_common><accessor source="#ta" count="4" stride="2"><param name="S" type="float"/>
        <param name="T" type="float"/></accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles material="m1" count="1"><input semantic="VERTEX" source="#v" offset="0"/>
      <input semantic="TEXCOORD" source="#tc" offset="1" set="0"/><p>0 0 1 1 2 2</p></triangles>
    <triangles material="m2" count="1"><input semantic="VERTEX" source="#v" offset="0"/>
      <input semantic="TEXCOORD" source="#tc" offset="1" set="0"/><p>0 0 2 2 3 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="n"><translate>0 0 0.5</translate>
    <instance_geometry url="#geo"><bind_material><technique_common>
      <instance_material symbol="m1" target="#mat"><bind_vertex_input semantic="uv" input_semantic="TEXCOORD" input_set="0"/></instance_material>
      <instance_material symbol="m2" target="#mat2"/>
    </technique_common></bind_material></instance_geometry></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";

class Assimp : public test::FileTest {
 protected:
  void TearDown() override {
    unsetenv("MVR_IMPORT");
    unsetenv("MVR_IMPORT_SECONDS");
    FileTest::TearDown();
  }
  void expectError(const std::string& path, const std::string& what) {
    test::expectOneLineError([&] { loadMesh(path); }, path, what);
  }
};

TEST_F(Assimp, ColladaGeometryMaterialsAndTexture) {
  fs::create_directories(dir_ / "textures");
  test::writeRedPng(dir_ / "textures" / "red.png", 4);  // named Textures\RED.png in the file
  const Scene s = loadMesh(write("quad.dae", kCollada));
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const glm::vec3& p : s.positions) EXPECT_FLOAT_EQ(p.z, 0.5f);  // the node's transform, flattened
  ASSERT_EQ(s.uvs.size(), s.positions.size());
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& red = s.materials[s.materialIds[0]];
  EXPECT_EQ(red.name, "redtex");
  EXPECT_EQ(fs::path(red.texture), dir_ / "textures" / "red.png");
  EXPECT_EQ(red.specular, glm::vec3(0.5f));
  EXPECT_EQ(red.shininess, 40.0f);
  const Material& blue = s.materials[s.materialIds[1]];
  EXPECT_NEAR(glm::distance(blue.diffuse, glm::vec3(0.2f, 0.4f, 0.6f)), 0.0f, 1e-6f);
  EXPECT_EQ(blue.specular, glm::vec3(0.0f));  // Lambert: no highlight
  EXPECT_TRUE(blue.twoSided);
  bool found = false;
  for (const std::string& w : s.warnings) found = found || w.find("read as ") != std::string::npos;
  EXPECT_TRUE(found) << ::testing::PrintToString(s.warnings);
}

// A Collada file saved as UTF-16 (with its declaration saying so): the
// same quad as the UTF-8 file's.
TEST_F(Assimp, Utf16ColladaIsReadAsItsUtf8) {
  std::string text = kCollada;
  text.replace(text.find("utf-8"), 5, "UTF-16");
  std::string wide = "\xff\xfe";
  for (char c : text) wide += std::string{c, '\0'};
  const Scene s = loadMesh(write("wide.dae", wide));
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const glm::vec3& p : s.positions) EXPECT_FLOAT_EQ(p.z, 0.5f);
  bool said = false;
  for (const std::string& w : s.warnings) said = said || w.find("UTF-16 text read as UTF-8") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(s.warnings);
}

// Blanks before a number list's values (valid Collada, which assimp
// reads as a number and refuses): the same colour and shininess.
TEST_F(Assimp, BlanksBeforeColladaNumbersAreDropped) {
  std::string text = kCollada;
  text.replace(text.find("<color>0.2"), 10, "<color>  \n 0.2");
  text.replace(text.find("<float>40"), 9, "<float> 40");
  const Scene s = loadMesh(write("blanks.dae", text));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_NEAR(glm::distance(s.materials[s.materialIds[1]].diffuse, glm::vec3(0.2f, 0.4f, 0.6f)), 0.0f, 1e-6f);
  EXPECT_EQ(s.materials[s.materialIds[0]].shininess, 40.0f);
  bool said = false;
  for (const std::string& w : s.warnings) said = said || w.find("blanks before number lists") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(s.warnings);
}

TEST_F(Assimp, FailuresAreOneLine) {
  expectError(write("junk.fbx", "this is no FBX file"), "");
  // A binary FBX whose zero bytes became blanks (one of assimp's test files).
  expectError(write("blanks.fbx", std::string("Kaydara FBX Binary   \x1a \x84\x1c  ") + std::string(64, ' ')),
              "binary FBX with its zero bytes replaced (byte 20 is 32, not 0)");
  expectError(write("cut.dae", std::string(kCollada).substr(0, 700)), "");
  expectError((dir_ / "absent.3ds").string(), "no such model file");
  expectError(write("m.xyz", "x"), "not a model format mvr reads ('.xyz')");
  // An importer that crashes, and none at all.
  const std::string crash = write("crash.sh", "#!/bin/sh\nkill -SEGV $$\n");
  fs::permissions(crash, fs::perms::owner_all);
  setenv("MVR_IMPORT", crash.c_str(), 1);
  expectError(write("quad.dae", kCollada), "the importer (assimp) failed on this file (signal 11)");
  setenv("MVR_IMPORT", (dir_ / "none").c_str(), 1);
  expectError((dir_ / "quad.dae").string(), "cannot start");
  // One that hangs is killed at the time limit (MVR_IMPORT_SECONDS here).
  const std::string hang = write("hang.sh", "#!/bin/sh\nexec sleep 60\n");
  fs::permissions(hang, fs::perms::owner_all);
  setenv("MVR_IMPORT", hang.c_str(), 1);
  setenv("MVR_IMPORT_SECONDS", "1", 1);
  const auto start = std::chrono::steady_clock::now();
  expectError((dir_ / "quad.dae").string(), "the importer (assimp) took more than 1 s");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

// The quad deformed by a skin of one joint (its own node, weight 1): a
// controller over the geometry, instanced where the geometry was.
std::string skinnedCollada() {
  std::string text = kCollada;
  const char* const controllers = R"(<library_controllers><controller id="ctl"><skin source="#geo">
    <bind_shape_matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</bind_shape_matrix>
    <source id="joints"><Name_array id="ja" count="1">n</Name_array><technique_common>
      <accessor source="#ja" count="1" stride="1"><param name="JOINT" type="name"/></accessor></technique_common></source>
    <source id="binds"><float_array id="ba" count="16">1 0 0 0 0 1 0 0 0 0 1 -0.5 0 0 0 1</float_array><technique_common>
      <accessor source="#ba" count="1" stride="16"><param name="TRANSFORM" type="float4x4"/></accessor></technique_common></source>
    <source id="weights"><float_array id="wa" count="1">1</float_array><technique_common>
      <accessor source="#wa" count="1" stride="1"><param name="WEIGHT" type="float"/></accessor></technique_common></source>
    <joints><input semantic="JOINT" source="#joints"/><input semantic="INV_BIND_MATRIX" source="#binds"/></joints>
    <vertex_weights count="4"><input semantic="JOINT" source="#joints" offset="0"/>
      <input semantic="WEIGHT" source="#weights" offset="1"/><vcount>1 1 1 1</vcount><v>0 0 0 0 0 0 0 0</v></vertex_weights>
  </skin></controller></library_controllers>
  )";
  text.insert(text.find("<library_visual_scenes>"), controllers);
  text.replace(text.find("<instance_geometry url=\"#geo\">"), 30, "<instance_controller url=\"#ctl\"><skeleton>#n</skeleton>");
  text.replace(text.find("</instance_geometry>"), 20, "</instance_controller>");
  return text;
}

// Assimp 5.2 fails outright on some well-formed skins (Debian's
// library_animation_clips.dae: out of memory). Here an importer that
// crashes on any skin stands for it: the quad is read again with its
// controller as the geometry it deforms, and says so.
TEST_F(Assimp, ASkinAssimpFailsOnIsDrawnUndeformed) {
  const std::string real = (fs::read_symlink("/proc/self/exe").parent_path() / "mvr-import").string();
  const std::string importer = write("fails-on-skins.sh", "#!/bin/sh\ngrep -q instance_controller \"$1\" && kill -SEGV $$\nexec '" + real + "' \"$1\"\n");
  fs::permissions(importer, fs::perms::owner_all);
  setenv("MVR_IMPORT", importer.c_str(), 1);
  const std::string path = write("skinned.dae", skinnedCollada());
  const Scene s = loadMesh(path);
  ASSERT_EQ(s.triangles.size(), 2u);
  for (const glm::vec3& p : s.positions) EXPECT_FLOAT_EQ(p.z, 0.5f);
  bool said = false;
  for (const std::string& w : s.warnings) said = said || w.find("assimp failed on its skins and morphs") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(s.warnings);
  // A file without a skin that crashes the importer still fails.
  setenv("MVR_IMPORT", write("crash.sh", "#!/bin/sh\nkill -SEGV $$\n").c_str(), 1);
  fs::permissions(dir_ / "crash.sh", fs::perms::owner_all);
  expectError(write("quad.dae", kCollada), "the importer (assimp) failed on this file (signal 11)");
  // The real assimp reads this skin itself: no second reading.
  unsetenv("MVR_IMPORT");
  for (const std::string& w : loadMesh(path).warnings) EXPECT_EQ(w.find("assimp failed"), std::string::npos) << w;
}

}  // namespace
}  // namespace mvr
