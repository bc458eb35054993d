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

// A quad with normals and two morph targets: target 0 lifts its top edge
// by 1 in z and tilts every normal by (0, -0.5, 0); target 1 moves its
// right edge by 0.5 in x (no normals). Its weights go LINEAR from (0, 0)
// at t = 0 to (1, 0.5) at t = 2: (t / 2, t / 4) between. animated = false:
// no animation, the node's weights set to those at t instead.
inline std::string writeMorphGltf(const std::filesystem::path& path, bool animated, double t = 0.0) {
  using Json = nlohmann::json;
  Document d;
  const int quad = d.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  const int normals = d.positions({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  const int lift = d.positions({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1});
  const int tilt = d.positions({0, -0.5f, 0, 0, -0.5f, 0, 0, -0.5f, 0, 0, -0.5f, 0});
  const int widen = d.positions({0, 0, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0, 0, 0});
  const int idx = d.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, 5123, "SCALAR", 6);
  d.json["meshes"] = Json::array({{{"weights", {0, 0}},
                                   {"primitives", Json::array({{{"attributes", {{"POSITION", quad}, {"NORMAL", normals}}},
                                                                {"indices", idx},
                                                                {"targets", Json::array({{{"POSITION", lift}, {"NORMAL", tilt}},
                                                                                         {{"POSITION", widen}}})}}})}}});
  Json node = {{"mesh", 0}};
  if (animated) {
    const int times = d.accessor(std::vector<float>{0, 2}, 5126, "SCALAR", 2);
    const int weights = d.accessor(std::vector<float>{0, 0, 1, 0.5f}, 5126, "SCALAR", 4);
    d.json["animations"] = Json::array({{{"name", "Morph"},
                                         {"samplers", Json::array({{{"input", times}, {"output", weights}}})},
                                         {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}})}}});
  } else {
    node["weights"] = {t / 2, t / 4};
  }
  d.json["nodes"] = Json::array({node});
  d.json["scenes"] = Json::array({{{"nodes", {0}}}});
  return d.write(path);
}

// A strip of two quads up the y axis, x in [-0.2, 0.2], y = 0, 1, 2,
// skinned to two joints: "root" at the origin and its child "tip" at
// (0, 1, 0), whose inverse bind matrix moves it back to the origin. Rows
// y = 0, 1, 2 weigh (root, tip) (1, 0), (0.5, 0.5), (0, 1). The mesh's own
// node is moved by (5, 0, 0), which a skinned mesh ignores (glTF's rule).
// The tip turns LINEAR about z from none at t = 0 to a quarter turn at
// t = 2 (45 t degrees). animated = false: the tip's rotation set to that
// at t instead.
inline std::string writeSkinnedGltf(const std::filesystem::path& path, bool animated, double t = 0.0) {
  using Json = nlohmann::json;
  Document d;
  const int strip = d.positions({-0.2f, 0, 0, 0.2f, 0, 0, -0.2f, 1, 0, 0.2f, 1, 0, -0.2f, 2, 0, 0.2f, 2, 0});
  const int normals = d.positions({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  const int idx = d.accessor(std::vector<uint16_t>{0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}, 5123, "SCALAR", 12);
  std::vector<uint8_t> rootAndTip;
  for (int v = 0; v < 6; ++v) rootAndTip.insert(rootAndTip.end(), {0, 1, 0, 0});
  const int joints = d.accessor(rootAndTip, 5121, "VEC4", 6);
  const int weights = d.accessor(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0,
                                                    0, 1, 0, 0, 0, 1, 0, 0}, 5126, "VEC4", 6);
  const int inverseBind = d.accessor(std::vector<float>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}, 5126, "MAT4", 2);
  d.json["meshes"] = Json::array(
      {{{"primitives", Json::array({{{"attributes", {{"POSITION", strip}, {"NORMAL", normals}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}},
                                     {"indices", idx}}})}}});
  d.json["skins"] = Json::array({{{"joints", {1, 2}}, {"inverseBindMatrices", inverseBind}}});
  const float h = std::sqrt(0.5f);
  Json tip = {{"name", "tip"}, {"translation", {0, 1, 0}}};
  if (animated) {
    const int times = d.accessor(std::vector<float>{0, 2}, 5126, "SCALAR", 2);
    const int turns = d.accessor(std::vector<float>{0, 0, 0, 1, 0, 0, h, h}, 5126, "VEC4", 2);
    d.json["animations"] = Json::array({{{"name", "Bend"},
                                         {"samplers", Json::array({{{"input", times}, {"output", turns}}})},
                                         {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}})}}});
  } else {
    const double half = 3.14159265358979 / 8 * t;  // half of 45 t degrees
    tip["rotation"] = {0, 0, std::sin(half), std::cos(half)};
  }
  d.json["nodes"] = Json::array({{{"mesh", 0}, {"skin", 0}, {"translation", {5, 0, 0}}},
                                 {{"name", "root"}, {"children", {2}}}, tip});
  d.json["scenes"] = Json::array({{{"nodes", {0, 1}}}});
  return d.write(path);
}

}  // namespace mvr::test
