// Writes a skinned glTF character stand-in for the skinning benchmarks
// (issue 56): a tube of about N vertices up +y, its skeleton a chain of J
// joints up the same axis, each vertex weighted to its two nearest joints
// (a tent), and a 2-second clip that bends every joint about z (a wave up
// the chain, 25 LINEAR keys). A GLB, as Blender exports one.
//   make_skinned --vertices 100000 --joints 60 --out tube.glb
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/cli/cli.h"
#include "apps/helpers/glb_writer.h"
#include "mvr/error.h"

namespace {

using Json = nlohmann::json;
using mvr::app::Glb;
constexpr float kLength = 2.0f, kPi = 3.14159265358979f;
constexpr int kAround = 32, kKeys = 25;

void writeTube(int vertices, int joints, const std::string& path) {
  const int rings = std::max(2, vertices / kAround);
  const float step = kLength / float(joints);
  std::vector<float> positions, normals, weights;
  std::vector<uint16_t> influences;
  for (int r = 0; r < rings; ++r) {
    const float y = kLength * float(r) / float(rings - 1);
    const float radius = 0.15f + 0.05f * std::sin(6.0f * y);
    const float f = std::min(y / step, float(joints - 1));
    const int j0 = std::min(int(f), joints - 1), j1 = std::min(j0 + 1, joints - 1);
    const float w1 = j1 == j0 ? 0.0f : f - float(j0);
    for (int a = 0; a < kAround; ++a) {
      const float t = 2.0f * kPi * float(a) / kAround, c = std::cos(t), s = std::sin(t);
      positions.insert(positions.end(), {radius * c, y, radius * s});
      normals.insert(normals.end(), {c, 0.0f, s});
      influences.insert(influences.end(), {uint16_t(j0), uint16_t(j1), 0, 0});
      weights.insert(weights.end(), {1.0f - w1, w1, 0.0f, 0.0f});
    }
  }
  std::vector<uint32_t> indices;
  for (int r = 0; r + 1 < rings; ++r)
    for (int a = 0; a < kAround; ++a) {
      const uint32_t p = uint32_t(r * kAround + a), q = uint32_t(r * kAround + (a + 1) % kAround);
      indices.insert(indices.end(), {p, p + kAround, q, q, p + kAround, q + kAround});
    }
  Glb g("mvr make_skinned");
  const size_t n = positions.size() / 3;
  const int pos = g.accessor(positions, 5126, "VEC3", n);
  g.json["accessors"][pos]["min"] = {-0.2, 0.0, -0.2};
  g.json["accessors"][pos]["max"] = {0.2, kLength, 0.2};
  const Json attributes = {{"POSITION", pos}, {"NORMAL", g.accessor(normals, 5126, "VEC3", n)},
                           {"JOINTS_0", g.accessor(influences, 5123, "VEC4", n)},
                           {"WEIGHTS_0", g.accessor(weights, 5126, "VEC4", n)}};
  const int idx = g.accessor(indices, 5125, "SCALAR", indices.size());
  g.json["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.5, 0.3, 1.0}}, {"metallicFactor", 0.0}}}}});
  g.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", attributes}, {"indices", idx}, {"material", 0}}})}}});
  // Nodes: 0 the mesh, 1.. the joints, each a child of the one before.
  Json nodes = Json::array({{{"name", "tube"}, {"mesh", 0}, {"skin", 0}}});
  std::vector<float> inverseBind, times;
  Json skinJoints = Json::array(), samplers = Json::array(), channels = Json::array();
  for (int k = 0; k < kKeys; ++k) times.push_back(2.0f * float(k) / float(kKeys - 1));
  const int input = g.accessor(times, 5126, "SCALAR", times.size());
  for (int j = 0; j < joints; ++j) {
    Json node = {{"name", "joint" + std::to_string(j)}, {"translation", {0.0, j == 0 ? 0.0 : step, 0.0}}};
    if (j + 1 < joints) node["children"] = {j + 2};
    nodes.push_back(node);
    skinJoints.push_back(j + 1);
    const float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -step * float(j), 0, 1};
    inverseBind.insert(inverseBind.end(), m, m + 16);
    std::vector<float> turns;  // a wave up the chain: about z, 1.5 turns in all at its crest
    for (float t : times) {
      const float half = 0.5f * (1.5f * kPi / float(joints)) * std::sin(kPi * t + 0.3f * float(j));
      turns.insert(turns.end(), {0.0f, 0.0f, std::sin(half), std::cos(half)});
    }
    samplers.push_back({{"input", input}, {"output", g.accessor(turns, 5126, "VEC4", times.size())}});
    channels.push_back({{"sampler", j}, {"target", {{"node", j + 1}, {"path", "rotation"}}}});
  }
  g.json["nodes"] = nodes;
  g.json["skins"] = Json::array({{{"joints", skinJoints}, {"inverseBindMatrices", g.accessor(inverseBind, 5126, "MAT4", size_t(joints))}}});
  g.json["animations"] = Json::array({{{"name", "Wave"}, {"samplers", samplers}, {"channels", channels}}});
  g.json["scenes"] = Json::array({{{"nodes", {0, 1}}}});
  g.json["scene"] = 0;
  g.write(path);
  std::fprintf(stderr, "make_skinned: %zu vertices, %zu triangles, %d joints -> %s\n", n, indices.size() / 3, joints,
               path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    CLI::App app("Writes a skinned, animated tube as GLB (a character stand-in for the benchmarks).", "make_skinned");
    int vertices = 100000, joints = 60;
    std::string out;
    app.add_option("--vertices", vertices, "about this many vertices")->check(CLI::Range(64, 20000000))->capture_default_str();
    app.add_option("--joints", joints, "joints in the chain")->check(CLI::Range(1, 1000))->capture_default_str();
    app.add_option("--out", out, "the GLB file to write")->type_name("FILE.glb")->required();
    if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
    writeTube(vertices, joints, out);
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_skinned: %s\n", e.what());
    return 1;
  }
}
