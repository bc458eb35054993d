// OBJ files with their MTL materials, written by the tests
// (mvr/assets/obj_io.h): usemtl groups and the mapping of Kd, Ks, Ns, Ke,
// map_Kd and map_Ke; paths written on Windows; statements not read, named once;
// polygons, texture seams and vertex colours; a textured quad whose
// colour proves the texture came through, MVR against SVR.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "mvr/error.h"
#include "mvr/assets/mesh_io.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/file_test.h"
#include "tests/support/render_helpers.h"
#include "tests/support/solid_png.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

class Obj : public test::FileTest {};

bool anyWarning(const Scene& s, const std::string& text) {
  return std::any_of(s.warnings.begin(), s.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// A unit square in z = 0 as two triangles with texture coordinates.
const char* const kSquare =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n";

TEST_F(Obj, UsemtlGroupsAndTheirMaterials) {
  // The MTL lies in a subfolder and names its texture from there, written
  // on Windows: backslashes, and a case the disk does not have.
  fs::create_directories(dir_ / "mats" / "tex");
  test::writeRedPng(dir_ / "mats" / "tex" / "red.png", 4);
  write("mats/lib.mtl",
        "newmtl plain\nKd 0.5 0.25 1\nKs 0 0 0\nNs 10\nKe 1 0.5 0.5\nmap_Ke tex/red.png\n"
        "newmtl shiny\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 250\nmap_Kd TEX\\Red.PNG\nPr 0.5\nfoo 1\n");
  const std::string obj = write("m.obj", std::string("mtllib mats/lib.mtl\n") + kSquare +
                                             "f 1/1/1 2/2/1 3/3/1\n"  // before any usemtl: the default
                                             "usemtl plain\nf 1/1/1 3/3/1 4/4/1\n"
                                             "usemtl shiny\nvp 0.5 0.5\nf 1/1/1 2/2/1 4/4/1\n"
                                             "usemtl plain\nf 2/2/1 3/3/1 4/4/1\ncurv 0 1 1 2\n");
  const Scene s = loadMesh(obj);
  ASSERT_EQ(s.triangles.size(), 4u);
  ASSERT_EQ(s.materials.size(), 3u);  // in the order first used
  EXPECT_EQ(s.materialIds, (std::vector<uint32_t>{0, 1, 2, 1}));
  EXPECT_EQ(s.materials[0].diffuse, Material{}.diffuse);
  const Material& plain = s.materials[1];
  EXPECT_EQ(plain.name, "plain");
  EXPECT_EQ(plain.diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(plain.specular, glm::vec3(0.0f));
  EXPECT_TRUE(plain.texture.empty());
  EXPECT_EQ(plain.emission, glm::vec3(1.0f, 0.5f, 0.5f));  // Ke, scaling map_Ke's texels
  EXPECT_EQ(fs::path(plain.emissionTexture), dir_ / "mats" / "tex" / "red.png");
  const Material& shiny = s.materials[2];
  EXPECT_EQ(shiny.specular, glm::vec3(0.5f));
  EXPECT_EQ(shiny.shininess, 250.0f);
  EXPECT_EQ(fs::path(shiny.texture), dir_ / "mats" / "tex" / "red.png");
  EXPECT_TRUE(anyWarning(s, "backslashes in file names read as slashes")) << ::testing::PrintToString(s.warnings);
  EXPECT_TRUE(anyWarning(s, "map_Kd 'TEX\\Red.PNG' read as ")) << ::testing::PrintToString(s.warnings);
  EXPECT_TRUE(anyWarning(s, "statements not read: vp (line 15), curv (line 19)")) << ::testing::PrintToString(s.warnings);
  EXPECT_TRUE(anyWarning(s, "material 'shiny': not read: ")) << ::testing::PrintToString(s.warnings);
  EXPECT_TRUE(anyWarning(s, "faces of no material the MTL files define are drawn as the default"));
  // Every corner had a normal: the file's, and one vertex per distinct
  // position and texture coordinate.
  EXPECT_EQ(s.positions.size(), 4u);
  for (const glm::vec3& n : s.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  EXPECT_EQ(s.uvs[s.triangles[0].y], glm::vec2(1, 0));
}

TEST_F(Obj, PolygonsSeamsAndColours) {
  // A pentagon (three triangles) with no normals, and a texture seam: the
  // corner at (1, 0, 0) has two texture coordinates, so two vertices,
  // which share one smooth normal.
  const std::string obj = write("p.obj",
                                "v 0 0 0 1 0 0\nv 1 0 0\nv 1.5 1 0.5\nv 0.5 1.5 0\nv -0.5 1 0.5\nvt 0 0\nvt 1 0\nvt 0.5 1\n"
                                "f 1/1 2/2 3/3 4/3 5/3\nf 2/1 1/1 5/3\nl 1 2\n");
  const Scene s = loadMesh(obj);
  EXPECT_EQ(s.triangles.size(), 4u + 8);  // the line a prism of 8 after them
  EXPECT_TRUE(anyWarning(s, "points and lines drawn as small solids"));
  EXPECT_EQ(s.positions.size(), 6u + 8);  // 5 positions, one twice; then the prism's
  std::vector<size_t> atCorner;
  for (size_t v = 0; v < 6; ++v)
    if (s.positions[v] == glm::vec3(1, 0, 0)) atCorner.push_back(v);
  ASSERT_EQ(atCorner.size(), 2u);
  EXPECT_EQ(s.normals[atCorner[0]], s.normals[atCorner[1]]);
  EXPECT_NE(s.uvs[atCorner[0]], s.uvs[atCorner[1]]);
  for (size_t v = 0; v < 6; ++v)  // vertex 1's colour; the others white
    EXPECT_EQ(s.colors[v], s.positions[v] == glm::vec3(0.0f) ? glm::vec3(1, 0, 0) : glm::vec3(1.0f)) << v;
}

TEST_F(Obj, MissingLibrariesAndMapsAreWarnings) {
  write("m.mtl", "newmtl a\nKd 0.2 0.4 0.6\nmap_Kd absent.png\nd 0.5\nKe 1 0 0\n");
  const Scene s = loadMesh(write("m.obj", std::string("mtllib gone.mtl m.mtl\n") + kSquare +
                                             "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n"));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].diffuse, glm::vec3(0.2f, 0.4f, 0.6f));
  EXPECT_TRUE(s.materials[0].texture.empty());
  EXPECT_EQ(s.materials[0].emission, glm::vec3(1, 0, 0));  // Ke
  for (const char* w : {"material library 'gone.mtl' not found", "map_Kd 'absent.png' not found: drawn untextured",
                        "transparency (d, Tr) drawn opaque",
                        "faces of no material the MTL files define"})
    EXPECT_TRUE(anyWarning(s, w)) << w << " in " << ::testing::PrintToString(s.warnings);
}

// tinyobjloader reads usemtl names to their first blank; 3ds Max writes
// names of several words (and some exporters a blank after the name).
TEST_F(Obj, MaterialNamesOfSeveralWords) {
  write("m.mtl", "newmtl Hard Shiny  White \nKd 1 0 0\nnewmtl Hard\nKd 0 1 0\n");
  const Scene s = loadMesh(write("m.obj", std::string("mtllib m.mtl\n") + kSquare +
                                             "usemtl Hard Shiny  White\nf 1 2 3\nusemtl Hard\nf 1 3 4\n"));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "Hard Shiny  White");
  EXPECT_EQ(s.materials[0].diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.materials[1].diffuse, glm::vec3(0, 1, 0));
  EXPECT_TRUE(s.warnings.empty()) << ::testing::PrintToString(s.warnings);
}

// A scene file's mesh entry: "material" is every face's, "materials"
// replaces the file's own by name.
TEST_F(Obj, SceneFileOverridesTheFilesMaterials) {
  write("m.mtl", "newmtl a\nKd 0.2 0.2 0.2\nnewmtl b\nKd 0.4 0.4 0.4\n");
  write("m.obj", std::string("mtllib m.mtl\n") + kSquare + "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 4\n");
  auto scene = [&](const std::string& entry) {
    return loadScene(write("s.json", R"({"materials": {"red": {"diffuse": [1, 0, 0]}}, "meshes": [{"file": "m.obj", )" +
                                         entry + "}]}"));
  };
  const Scene all = scene(R"("material": "red")");
  ASSERT_EQ(all.materials.size(), 1u);
  EXPECT_EQ(all.materials[0].diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(all.materialIds, (std::vector<uint32_t>{0, 0}));
  const Scene byName = scene(R"("materials": {"b": "red", "a": {"diffuse": [0, 1, 0]}})");
  ASSERT_EQ(byName.materials.size(), 2u);
  EXPECT_EQ(byName.materials[byName.materialIds[0]].diffuse, glm::vec3(0, 1, 0));
  EXPECT_EQ(byName.materials[byName.materialIds[1]].diffuse, glm::vec3(1, 0, 0));
  for (const auto& [entry, message] :
       {std::pair<std::string, std::string>{R"("materials": {"c": "red"})", "meshes[0].materials.c: the file has no material"},
        {R"("materials": {"a": "blue"})", "meshes[0].materials.a: no material \"blue\""},
        {R"("material": "red", "materials": {})", "exclude each other"}})
    test::expectOneLineError([&] { scene(entry); }, "s.json", message);
}

TEST_F(Obj, BadFilesAreOneLineErrors) {
  auto expectError = [&](const std::string& path, const std::string& what) {
    test::expectOneLineError([&] { loadScene(path); }, path, what);
  };
  expectError(write("uv.obj", std::string(kSquare) + "f 1/9 2/2 3/3\n"), "uv.obj:10: face refers to texture coordinate 9");
  expectError(write("empty.obj", "# nothing but this\n"), "mesh has no triangles");
  expectError(write("bright.obj", "v 0 0 0 0 0 3\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "vertex 0 has a colour outside [0, 1]");
  expectError((dir_ / "absent.obj").string(), "no such mesh file");
}

// A square textured by its MTL's map_Kd (one colour), lit head on: svr's
// and mvr's views show the texture's colour, and agree.
TEST_F(Obj, TexturedQuadMvrAgainstSvr) {
  test::sharedContext();
  test::writeRedPng(dir_ / "red.png", 8);
  write("q.mtl", "newmtl red\nKd 1 1 1\nKs 0 0 0\nmap_Kd red.png\n");
  Scene scene = loadScene(write("q.obj", std::string("mtllib q.mtl\n") + kSquare +
                                            "usemtl red\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"));
  scene.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  scene.ambient = glm::vec3(0.0f);
  const ShearingCamera cam(cameraFor(scene, 64, 48), 64, 48, 5);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  auto mvr = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink a = test::renderViews(*svr, cam), b = test::renderViews(*mvr, cam);
  const glm::vec4 c = a.views.at({0, 2}).linear(32, 24);
  EXPECT_NEAR(c.r, decodeSrgb8(test::kRed).r, 0.02f);
  EXPECT_GT(c.r, 5 * c.g);
  test::expectCloseOnAnyGl(test::compareViews(a, b), 0.99, 30.0, "OBJ textured quad, mvr cpu");
}

// A UTF-16 file (Windows' "Unicode"), either byte order: read as its UTF-8 text.
TEST_F(Obj, Utf16TextIsReadAsUtf8) {
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  for (bool big : {true, false}) {
    std::string wide = big ? "\xfe\xff" : "\xff\xfe";
    for (char c : text) wide += big ? std::string{'\0', c} : std::string{c, '\0'};
    const Scene s = loadMesh(write(big ? "be.obj" : "le.obj", wide));
    ASSERT_EQ(s.triangles.size(), 1u) << big;
    EXPECT_EQ(s.positions[s.triangles[0].y], glm::vec3(1, 0, 0));
    EXPECT_TRUE(anyWarning(s, "UTF-16 text read as UTF-8"));
  }
}

}  // namespace
}  // namespace mvr
