// glTF animations (mvr/scene_animation.h, issue 47): each interpolation by
// hand, and a loaded file posed at a time equal to the same file with its
// nodes' TRS or morph weights set to the values at that time (the "posed
// scene"), through a node hierarchy and a scene file's transform; morph
// targets and a two-joint skin checked vertex by vertex against sums done
// by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/gtc/quaternion.hpp>

#include "mvr/error.h"
#include "mvr/assets/mesh_io.h"
#include "mvr/assets/scene_io.h"
#include "mvr/scene_animation.h"
#include "mvr/scene_pose.h"
#include "tests/support/file_test.h"
#include "tests/support/animated_gltf.h"
#include "tests/support/gltf_document.h"

namespace mvr {
namespace {

using Json = nlohmann::json;
using Path = AnimationChannel::Path;
using Interpolation = AnimationChannel::Interpolation;

AnimationChannel channel(Path path, Interpolation how, std::vector<float> times, std::vector<float> values) {
  AnimationChannel c;
  c.path = path, c.interpolation = how, c.times = std::move(times), c.values = std::move(values);
  return c;
}

TEST(Animation, EachInterpolationByHand) {
  const auto linear = channel(Path::Translation, Interpolation::Linear, {0, 1}, {0, 0, 0, 4, 0, 0});
  EXPECT_EQ(linear.sample(0.25), glm::vec4(1, 0, 0, 0));
  EXPECT_EQ(linear.sample(-3.0), glm::vec4(0, 0, 0, 0));  // before the first key: the first value
  EXPECT_EQ(linear.sample(9.0), glm::vec4(4, 0, 0, 0));   // after the last: the last
  const auto step = channel(Path::Scale, Interpolation::Step, {0, 1}, {1, 1, 1, 2, 2, 2});
  EXPECT_EQ(step.sample(0.99), glm::vec4(1, 1, 1, 0));
  EXPECT_EQ(step.sample(1.0), glm::vec4(2, 2, 2, 0));
  // Hermite at s = 1/2 over dt = 2: v0 = 0, v1 = 1, out-tangent of key 0
  // b0 = 1, in-tangent of key 1 a1 = 0: 0.5 + (1/8 - 1/2 + 1/2) * 2 * 1 = 0.75.
  const auto cubic = channel(Path::Translation, Interpolation::CubicSpline, {0, 2},
                             {0, 0, 0, 0, 0, 0, 1, 0, 0, /* key 1: */ 0, 0, 0, 1, 0, 0, 0, 0, 0});
  EXPECT_NEAR(cubic.sample(1.0).x, 0.75f, 1e-6f);
  // A quarter turn about y, halfway: an eighth, by slerp.
  const float h = std::sqrt(0.5f);
  const auto turn = channel(Path::Rotation, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, h, 0, h});
  const glm::vec4 q = turn.sample(0.5);
  EXPECT_NEAR(q.y, std::sin(glm::radians(22.5f)), 1e-6f);
  EXPECT_NEAR(q.w, std::cos(glm::radians(22.5f)), 1e-6f);
}

// A weights channel carries one value per morph target per key.
TEST(Animation, WeightsChannelSamplesEveryTarget) {
  auto weights = channel(Path::Weights, Interpolation::Linear, {0, 2}, {0, 1, 1, 0});
  weights.weights = 2;
  float w[2];
  weights.sample(0.5, w);
  EXPECT_FLOAT_EQ(w[0], 0.25f);
  EXPECT_FLOAT_EQ(w[1], 0.75f);
  // CUBICSPLINE with zero tangents: the smoothstep 3s^2 - 2s^3, 0.5 at s = 0.5.
  auto cubic = channel(Path::Weights, Interpolation::CubicSpline, {0, 2}, {0, 0, 0, 4, 0, 0, 0, 0, 2, 0, 0, 0});
  cubic.weights = 2;
  cubic.sample(1.0, w);
  EXPECT_FLOAT_EQ(w[0], 1.0f);
  EXPECT_FLOAT_EQ(w[1], 2.0f);
}

void expectSameVertices(const Scene& got, const Scene& want, const std::string& what) {
  ASSERT_EQ(got.positions.size(), want.positions.size()) << what;
  for (size_t v = 0; v < want.positions.size(); ++v) {
    EXPECT_NEAR(glm::distance(got.positions[v], want.positions[v]), 0.0f, 1e-5f) << what << " vertex " << v;
    EXPECT_NEAR(glm::distance(got.normals[v], want.normals[v]), 0.0f, 1e-5f) << what << " vertex " << v;
  }
}

class AnimatedGltf : public test::FileTest {
 protected:
  std::string write(const std::string& name, bool animated, double t = 0.0) {
    return test::writeAnimatedGltf(dir_ / name, animated, t);
  }
};

TEST_F(AnimatedGltf, PosedEqualsTheFileWithThoseValues) {
  Scene scene = loadMesh(write("anim.gltf", true));
  ASSERT_EQ(scene.animations.size(), 1u);
  ASSERT_EQ(scene.animations[0]->clips.size(), 1u);
  EXPECT_EQ(scene.animations[0]->clips[0].name, "Walk");
  EXPECT_DOUBLE_EQ(animationLength(scene, ""), 2.0);
  EXPECT_TRUE(hasClip(scene, "Walk"));
  EXPECT_FALSE(hasClip(scene, "Run"));
  for (double t : {0.0, 0.7, 1.5, 2.0}) {
    poseAnimations(scene, t, "", glm::mat4(1.0f));
    const Scene want = loadMesh(write("posed.gltf", false, t));
    ASSERT_EQ(want.positions.size(), scene.positions.size());
    for (size_t v = 0; v < want.positions.size(); ++v) {
      EXPECT_NEAR(glm::distance(scene.positions[v], want.positions[v]), 0.0f, 1e-5f) << "t " << t << " vertex " << v;
      EXPECT_NEAR(glm::distance(scene.normals[v], want.normals[v]), 0.0f, 1e-5f) << "t " << t << " vertex " << v;
    }
  }
  // A clip of another name does not play: the rest pose.
  poseAnimations(scene, 1.5, "Run", glm::mat4(1.0f));
  const Scene rest = loadMesh(write("rest.gltf", false, 0.0));
  EXPECT_NEAR(glm::distance(scene.positions[2], rest.positions[2]), 0.0f, 1e-5f);
}

// Through a scene file: the entry's transform applies after the animation,
// and the animation follows the vertices to where the scene put them.
TEST_F(AnimatedGltf, InASceneFileAfterAnotherMesh) {
  write("anim.gltf", true);
  write("posed.gltf", false, 0.7);
  const char* entries = R"({"file": "other.obj"}, {"file": "%s", "transform": {"translate": [1, 2, 3], "rotate": [30, 0, 1, 0]}})";
  std::ofstream(dir_ / "other.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  char text[256];
  std::snprintf(text, sizeof text, entries, "anim.gltf");
  std::ofstream(dir_ / "anim.json") << "{\"meshes\": [" << text << "]}";
  std::snprintf(text, sizeof text, entries, "posed.gltf");
  std::ofstream(dir_ / "posed.json") << "{\"meshes\": [" << text << "]}";
  Scene scene = loadScene((dir_ / "anim.json").string());
  const Scene want = loadScene((dir_ / "posed.json").string());
  poseAnimations(scene, 0.7, "", glm::mat4(1.0f));
  ASSERT_EQ(want.positions.size(), scene.positions.size());
  for (size_t v = 0; v < want.positions.size(); ++v)
    EXPECT_NEAR(glm::distance(scene.positions[v], want.positions[v]), 0.0f, 1e-5f) << v;
}

// Weights (t/2, t/4) at t = 1: the top right corner (1, 1, 0) + 0.5 (0,
// 0, 1) + 0.25 (0.5, 0, 0); its normal (0, 0, 1) + 0.5 (0, -0.5, 0),
// normalised. The bottom left corner is in no target.
TEST_F(AnimatedGltf, MorphTargetsByHand) {
  Scene scene = loadMesh(test::writeMorphGltf(dir_ / "morph.gltf", true));
  ASSERT_EQ(scene.positions.size(), 4u);
  EXPECT_EQ(scene.positions[2], glm::vec3(1, 1, 0));  // at rest: the mesh's weights, (0, 0)
  poseAnimations(scene, 1.0, "", glm::mat4(1.0f));
  EXPECT_NEAR(glm::distance(scene.positions[2], glm::vec3(1.125f, 1, 0.5f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(scene.normals[2], glm::normalize(glm::vec3(0, -0.25f, 1))), 0.0f, 1e-6f);
  EXPECT_EQ(scene.positions[0], glm::vec3(-1, -1, 0));
  for (double t : {0.5, 1.5, 2.0, 3.0}) {
    poseAnimations(scene, t, "", glm::mat4(1.0f));
    expectSameVertices(scene, loadMesh(test::writeMorphGltf(dir_ / "posed.gltf", false, std::min(t, 2.0))),
                       "t " + std::to_string(t));
  }
}

// The tip turned by theta = 45 degrees at t = 1: a vertex all on the tip
// turns about (0, 1, 0); one half on each joint is the mean of where each
// joint puts it. The mesh node's translation (5, 0, 0) is ignored.
TEST_F(AnimatedGltf, SkinByHand) {
  Scene scene = loadMesh(test::writeSkinnedGltf(dir_ / "skin.gltf", true));
  ASSERT_EQ(scene.positions.size(), 6u);
  EXPECT_NEAR(glm::distance(scene.positions[0], glm::vec3(-0.2f, 0, 0)), 0.0f, 1e-6f);  // the bind pose
  EXPECT_NEAR(glm::distance(scene.positions[5], glm::vec3(0.2f, 2, 0)), 0.0f, 1e-6f);
  poseAnimations(scene, 1.0, "", glm::mat4(1.0f));
  const float c = std::cos(glm::radians(45.0f)), s = std::sin(glm::radians(45.0f));
  auto turned = [&](glm::vec3 p) { return glm::vec3(c * p.x - s * p.y, s * p.x + c * p.y, p.z); };  // about z
  const glm::vec3 tipOf5 = turned(glm::vec3(0.2f, 1, 0)) + glm::vec3(0, 1, 0);
  const glm::vec3 halfOf3 = 0.5f * glm::vec3(0.2f, 1, 0) + 0.5f * (turned(glm::vec3(0.2f, 0, 0)) + glm::vec3(0, 1, 0));
  EXPECT_NEAR(glm::distance(scene.positions[5], tipOf5), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(scene.positions[3], halfOf3), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(scene.positions[1], glm::vec3(0.2f, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(scene.normals[5], glm::vec3(0, 0, 1)), 0.0f, 1e-6f);
  for (double t : {0.5, 1.5, 2.0}) {
    poseAnimations(scene, t, "", glm::mat4(1.0f));
    expectSameVertices(scene, loadMesh(test::writeSkinnedGltf(dir_ / "posed.gltf", false, t)), "t " + std::to_string(t));
  }
}

TEST_F(AnimatedGltf, BadSkinsAndWeightsAreOneLineErrors) {
  std::string text = test::writeSkinnedGltf(dir_ / "skin.gltf", false);
  Json doc = Json::parse(std::ifstream(text));
  doc["skins"][0]["joints"] = {1};  // JOINTS_0 names joint 1 of one
  std::ofstream(dir_ / "one_joint.gltf") << doc.dump();
  const std::string oneJoint = (dir_ / "one_joint.gltf").string();
  test::expectOneLineError([&] { loadMesh(oneJoint); }, oneJoint, "JOINTS_0 names joint 1 of a skin of 1");
  doc = Json::parse(std::ifstream(test::writeMorphGltf(dir_ / "morph.gltf", true)));
  doc["accessors"][doc["animations"][0]["samplers"][0]["output"].get<int>()]["count"] = 3;
  std::ofstream(dir_ / "bad_weights.gltf") << doc.dump();
  const std::string badWeights = (dir_ / "bad_weights.gltf").string();
  test::expectOneLineError([&] { loadMesh(badWeights); }, badWeights, "animation output of weights does not match its times");
}

TEST_F(AnimatedGltf, BadSamplersAreOneLineErrors) {
  test::Document d;
  const int tetra = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int times = d.accessor(std::vector<float>{1, 0}, 5126, "SCALAR", 2);
  const int moves = d.accessor(std::vector<float>{0, 0, 0, 1, 0, 0}, 5126, "VEC3", 2);
  d.json["meshes"] = Json::array({{{"primitives", Json::array({{{"attributes", {{"POSITION", tetra}}}}})}}});
  d.json["nodes"] = Json::array({{{"mesh", 0}}});
  d.json["animations"] = Json::array({{{"samplers", Json::array({{{"input", times}, {"output", moves}}})},
                                       {"channels", Json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}})}}});
  const std::string path = d.write(dir_ / "falling.gltf");
  test::expectOneLineError([&] { loadMesh(path); }, path, "animation times must rise");
}

}  // namespace
}  // namespace mvr
