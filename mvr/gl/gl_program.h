#pragma once
// Shader compilation and linking with errors that name the shader.
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"

namespace mvr::gl {

struct ShaderStage {
  GLenum type;
  std::string source;
};

// name appears in errors: "shader 'svr' (vertex): 0:12(3): error: ..."
Program linkProgram(std::string_view name, std::initializer_list<ShaderStage> stages);

// Vertex stage of one triangle covering the viewport (draw 3 vertices, no
// attributes): for full-screen passes.
extern const char* const kFullScreenTriangleVertex;

// "#version 450 core\n" plus defines, so one source serves several variants.
std::string glslHeader(std::initializer_list<std::string_view> defines = {});

// By name, the location looked up once per program (Program::location).
void setUniform(const Program& p, const char* name, int v);
void setUniform(const Program& p, const char* name, GLuint v);
void setUniform(const Program& p, const char* name, double v);
void setUniform(const Program& p, const char* name, const glm::dvec2& v);
void setUniform(const Program& p, const char* name, float v);
void setUniform(const Program& p, const char* name, const glm::vec2& v);
void setUniform(const Program& p, const char* name, const glm::vec3& v);
void setUniform(const Program& p, const char* name, const glm::vec4& v);
void setUniform(const Program& p, const char* name, const glm::mat3& v);
void setUniform(const Program& p, const char* name, const glm::mat4& v);
void setUniform(const Program& p, const char* name, std::span<const float> v);  // float[]

// A compute dispatch of the current program and the barrier that makes
// its writes visible to what reads them next (storage buffers by default).
inline void dispatch(GLuint x, GLuint y = 1, GLuint z = 1, GLbitfield barrier = GL_SHADER_STORAGE_BARRIER_BIT) {
  DispatchCompute(x, y, z);
  if (barrier) MemoryBarrier(barrier);
}

}  // namespace mvr::gl
