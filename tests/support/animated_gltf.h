#pragma once
// An animated glTF for the animation tests, and the same file posed by hand.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/gltf_document.h"

namespace mvr::test {

// A parent node that moves (LINEAR translation, CUBICSPLINE scale) and
// turns (STEP rotation) over [0, 2], and a child that carries a
// tetrahedron without normals (flat ones, moved by the normal matrix).
// animated = false: the same file with the parent's TRS set to the
// values at time t instead.
inline std::string writeAnimatedGltf(const std::filesystem::path& path, bool animated, double t = 0.0) {
  using Json = nlohmann::json;
  Document d;
  const int tetra = d.positions({0, 0, 0.6f, 0.5f, -0.4f, 0, -0.5f, -0.4f, 0, 0, 0.5f, 0});
  const int idx = d.accessor(std::vector<uint16_t>{0, 1, 3, 0, 2, 1, 0, 3, 2, 1, 2, 3}, 5123, "SCALAR", 12);
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", tetra}}}, {"indices", idx}}})}}});
  const float h = std::sqrt(0.5f);
  Json parent = {{"children", {1}}, {"translation", {0, 0, 0}}};
  if (animated) {
    const int times = d.accessor(std::vector<float>{0, 2}, 5126, "SCALAR", 2);
    const int moves = d.accessor(std::vector<float>{0, 0, 0, 2, 1, 0}, 5126, "VEC3", 2);
    const int turns = d.accessor(std::vector<float>{0, 0, 0, 1, 0, h, 0, h}, 5126, "VEC4", 2);
    const int grows = d.accessor(std::vector<float>{0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 0, 0, 0}, 5126, "VEC3", 6);
    d.json["animations"] = Json::array(
        {{{"name", "Walk"},
          {"samplers", Json::array({{{"input", times}, {"output", moves}},
                                    {{"input", times}, {"output", turns}, {"interpolation", "STEP"}},
                                    {{"input", times}, {"output", grows}, {"interpolation", "CUBICSPLINE"}}})},
          {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                                    {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}},
                                    {{"sampler", 2}, {"target", {{"node", 0}, {"path", "scale"}}}}})}}});
  } else {
    // By hand at t: translation (t, t/2, 0); rotation the first key's
    // until 2 (STEP); scale by Hermite from 1 to 2 with the out-tangent of
    // key 0 (1, 1, 1) and the in-tangent of key 1 (1, 1, 1), dt = 2.
    const double s = t / 2, s2 = s * s, s3 = s2 * s;
    const double k = (2 * s3 - 3 * s2 + 1) * 1 + (s3 - 2 * s2 + s) * 2 * 1 + (-2 * s3 + 3 * s2) * 2 + (s3 - s2) * 2 * 1;
    parent["translation"] = {t, t / 2, 0};
    parent["rotation"] = t >= 2 ? Json{0, h, 0, h} : Json{0, 0, 0, 1};
    parent["scale"] = {k, k, k};
  }
  d.json["nodes"] = Json::array({parent, {{"mesh", 0}, {"translation", {0.3, 0, 0}}}});
  d.json["scenes"] = Json::array({{{"nodes", {0}}}});
  return d.write(path);
}

}  // namespace mvr::test
