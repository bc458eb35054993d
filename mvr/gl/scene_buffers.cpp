#include "mvr/gl/scene_buffers.h"

namespace mvr {

const char* const kSceneVertexInputs = R"(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aAlbedo;
layout(location = 3) in float aCull;
layout(location = 4) in float aMaterial;
layout(location = 5) in vec2 aUv;
)";

namespace {

void attach(GLuint vao, GLuint attrib, const gl::Buffer& buffer, int components) {
  gl::VertexArrayVertexBuffer(vao, attrib, buffer.id(), 0, GLsizei(components * sizeof(float)));
  gl::VertexArrayAttribFormat(vao, attrib, components, GL_FLOAT, GL_FALSE, 0);
  gl::VertexArrayAttribBinding(vao, attrib, attrib);
  gl::EnableVertexArrayAttrib(vao, attrib);
}

// GLSL reads the material index as a float attribute.
std::vector<float> vertexMaterials(const Scene& scene) {
  const std::vector<uint32_t> ids = scene.vertexMaterials();
  return std::vector<float>(ids.begin(), ids.end());
}

std::vector<glm::vec2> vertexUvs(const Scene& scene) {
  return scene.uvs.empty() ? std::vector<glm::vec2>(scene.vertexCount(), glm::vec2(0.0f)) : scene.uvs;
}

}  // namespace

void SceneBuffers::move(const Scene& scene) {
  // New buffers: makeBuffer's storage is immutable.
  positions_ = gl::makeBuffer(scene.positions.data(), scene.positions.size());
  normals_ = gl::makeBuffer(scene.normals.data(), scene.normals.size());
  attach(vao_.id(), 0, positions_, 3);
  attach(vao_.id(), 1, normals_, 3);
}

SceneBuffers::SceneBuffers(const Scene& scene, const std::vector<glm::vec3>& albedo,
                           const std::vector<float>& cullFlags)
    : positions_(gl::makeBuffer(scene.positions.data(), scene.positions.size())),
      normals_(gl::makeBuffer(scene.normals.data(), scene.normals.size())),
      albedo_(gl::makeBuffer(albedo.data(), albedo.size())),
      cull_(gl::makeBuffer(cullFlags.data(), cullFlags.size())),
      materials_(gl::makeBuffer(vertexMaterials(scene).data(), scene.vertexCount())),
      uvs_(gl::makeBuffer(vertexUvs(scene).data(), scene.vertexCount())),
      indices_(gl::makeBuffer(scene.triangles.data(), scene.triangles.size())),
      vao_(gl::VertexArray::create()),
      indexCount_(GLsizei(scene.triangles.size() * 3)) {
  attach(vao_.id(), 0, positions_, 3);
  attach(vao_.id(), 1, normals_, 3);
  attach(vao_.id(), 2, albedo_, 3);
  attach(vao_.id(), 3, cull_, 1);
  attach(vao_.id(), 4, materials_, 1);
  attach(vao_.id(), 5, uvs_, 2);
  gl::VertexArrayElementBuffer(vao_.id(), indices_.id());
}

void SceneBuffers::draw(int instances) const {
  if (instances == 1)
    gl::DrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
  else
    gl::DrawElementsInstanced(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr, instances);
}

void SceneBuffers::draw(const gl::Buffer& indices, GLsizei count) const {
  gl::VertexArrayElementBuffer(vao_.id(), indices.id());
  gl::DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
  gl::VertexArrayElementBuffer(vao_.id(), indices_.id());
}

}  // namespace mvr
