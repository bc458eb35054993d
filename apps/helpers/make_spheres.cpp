// Writes the metallic x roughness sphere grid that mvr's metallic-
// roughness shading is held to against three.js (issue 66): N x N UV
// spheres, metallic rising from 0 to 1 left to right, roughness from 0 to 1
// bottom to top, one base colour, lit by KHR_lights_punctual's lights in
// physical units (a sun and a bulb). A GLB, as Blender exports one.
//   make_spheres --grid 5 --out spheres.glb
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/cli/cli.h"
#include "apps/helpers/glb_writer.h"

namespace {

using mvr::app::Glb;
using Json = Glb::Json;
constexpr float kPi = 3.14159265358979f;

// A unit-radius UV sphere: positions (= normals), texture coordinates and
// triangle indices; the accessors' indices in g.
struct SphereAccessors {
  int position, normal, uv, indices;
};

SphereAccessors writeSphere(Glb& g, int segments) {
  const int rings = segments / 2;
  std::vector<float> p, uv;
  for (int r = 0; r <= rings; ++r) {
    const float theta = kPi * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * kPi * float(s) / float(segments);
      p.insert(p.end(), {std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)});
      uv.insert(uv.end(), {float(s) / float(segments), float(r) / float(rings)});
    }
  }
  std::vector<uint32_t> idx;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
      if (r > 0) idx.insert(idx.end(), {a, b, a + 1});
      if (r + 1 < rings) idx.insert(idx.end(), {a + 1, b, b + 1});
    }
  const size_t n = p.size() / 3;
  SphereAccessors a{g.accessor(p, 5126, "VEC3", n), 0, g.accessor(uv, 5126, "VEC2", n),
                    g.accessor(idx, 5125, "SCALAR", idx.size())};
  g.json["accessors"][size_t(a.position)]["min"] = {-1.0, -1.0, -1.0};
  g.json["accessors"][size_t(a.position)]["max"] = {1.0, 1.0, 1.0};
  a.normal = a.position;  // a unit sphere's normal is its position
  return a;
}

void writeGrid(int grid, int segments, bool lit, const std::string& path) {
  Glb g("mvr make_spheres");
  const SphereAccessors sphere = writeSphere(g, segments);
  Json materials = Json::array(), meshes = Json::array(), nodes = Json::array(), roots = Json::array();
  const float spacing = 1.0f, radius = 0.42f, half = 0.5f * float(grid - 1);
  for (int row = 0; row < grid; ++row)
    for (int col = 0; col < grid; ++col) {
      const double metallic = grid > 1 ? double(col) / (grid - 1) : 0.0;
      const double roughness = grid > 1 ? double(row) / (grid - 1) : 0.5;
      materials.push_back({{"name", "m" + std::to_string(col) + "r" + std::to_string(row)},
                           {"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.9, 0.55, 0.25, 1.0}},
                             {"metallicFactor", metallic},
                             {"roughnessFactor", roughness}}}});
      meshes.push_back({{"primitives", Json::array({{{"attributes", {{"POSITION", sphere.position},
                                                                      {"NORMAL", sphere.normal},
                                                                      {"TEXCOORD_0", sphere.uv}}},
                                                      {"indices", sphere.indices},
                                                      {"material", materials.size() - 1}}})}});
      roots.push_back(nodes.size());
      nodes.push_back({{"mesh", meshes.size() - 1},
                       {"translation", {spacing * (col - half), spacing * (row - half), 0.0}},
                       {"scale", {radius, radius, radius}}});
    }
  // A sun from the upper left front and a bulb to the right, in lux and
  // candela; none for a grid an environment lights alone.
  if (lit) {
    const Json lights = Json::array({{{"type", "directional"}, {"intensity", 2.5}, {"color", {1.0, 0.98, 0.95}}},
                                     {{"type", "point"}, {"intensity", 8.0}, {"color", {0.8, 0.9, 1.0}}}});
    roots.push_back(nodes.size());
    nodes.push_back({{"rotation", {-0.3250576, -0.3250576, 0.0, 0.8880738}},  // its -z turned to (1, -1, -1)
                     {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    roots.push_back(nodes.size());
    nodes.push_back({{"translation", {half + 1.0, 0.5, 2.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    g.json["extensionsUsed"] = {"KHR_lights_punctual"};
    g.json["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
  }
  g.json["materials"] = materials;
  g.json["meshes"] = meshes;
  g.json["nodes"] = nodes;
  g.json["scenes"] = Json::array({{{"nodes", roots}}});
  g.json["scene"] = 0;
  g.write(path);
  std::fprintf(stderr, "make_spheres: %d x %d spheres -> %s\n", grid, grid, path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    CLI::App app("Writes a metallic x roughness grid of spheres as GLB (the PBR reference fixture).", "make_spheres");
    int grid = 5, segments = 48;
    bool unlit = false;
    std::string out;
    app.add_option("--grid", grid, "spheres along each side")->check(CLI::Range(1, 16))->capture_default_str();
    app.add_option("--segments", segments, "segments around each sphere")->check(CLI::Range(8, 512))->capture_default_str();
    app.add_flag("--no-lights", unlit, "no KHR_lights_punctual lights (for an environment alone)");
    app.add_option("--out", out, "the GLB file to write")->type_name("FILE.glb")->required();
    if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
    writeGrid(grid, segments, !unlit, out);
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_spheres: %s\n", e.what());
    return 1;
  }
}
