#pragma once
// The scene's vertex data on the GPU, as the view renderers draw it:
// position, normal, albedo, cull flag, material index and texture
// coordinates per vertex; triangles as indices.
#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"

namespace mvr {

class SceneBuffers {
 public:
  SceneBuffers(const Scene& scene, const std::vector<glm::vec3>& albedo,
               const std::vector<float>& cullFlags);
  void bind() const { gl::BindVertexArray(vao_.id()); }
  void draw(int instances = 1) const;
  // The triangles of `indices` alone (three a triangle, count in all), with
  // the same vertices.
  void draw(const gl::Buffer& indices, GLsizei count) const;
  GLsizei indexCount() const { return indexCount_; }
  // The scene moved (mvr/scene_pose.h): its positions and normals again.
  void move(const Scene& scene);

 private:
  gl::Buffer positions_, normals_, albedo_, cull_, materials_, uvs_, indices_;
  gl::VertexArray vao_;
  GLsizei indexCount_;
};

// GLSL attribute declarations matching SceneBuffers' layout.
extern const char* const kSceneVertexInputs;

}  // namespace mvr
