#include "mvr/gl/gl_program.h"

#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "mvr/error.h"

namespace mvr::gl {
namespace {

const char* stageName(GLenum type) {
  switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    case GL_COMPUTE_SHADER: return "compute";
  }
  return "shader";
}

// Info logs are multi-line; errors must be one line.
std::string oneLine(std::string log) {
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  for (char& c : log)
    if (c == '\n') c = ';';
  return log;
}

}  // namespace

const char* const kFullScreenTriangleVertex = R"(
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.5, 1.0);
}
)";

Program linkProgram(std::string_view name, std::initializer_list<ShaderStage> stages) {
  Program program = Program::create();
  std::vector<Shader> shaders;
  for (const ShaderStage& stage : stages) {
    Shader shader(CreateShader(stage.type));
    const char* src = stage.source.c_str();
    ShaderSource(shader.id(), 1, &src, nullptr);
    CompileShader(shader.id());
    GLint ok = 0;
    GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      GetShaderInfoLog(shader.id(), sizeof log, nullptr, log);
      fail("shader '" + std::string(name) + "' (" + stageName(stage.type) + ")", oneLine(log));
    }
    AttachShader(program.id(), shader.id());
    shaders.push_back(std::move(shader));
  }
  LinkProgram(program.id());
  GLint ok = 0;
  GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    GetProgramInfoLog(program.id(), sizeof log, nullptr, log);
    fail("shader '" + std::string(name) + "' (link)", oneLine(log));
  }
  return program;
}

std::string glslHeader(std::initializer_list<std::string_view> defines) {
  std::string s = "#version 450 core\n";
  for (std::string_view d : defines) s += "#define " + std::string(d) + "\n";
  return s;
}

void setUniform(const Program& p, const char* name, int v) {
  ProgramUniform1i(p.id(), p.location(name), v);
}
void setUniform(const Program& p, const char* name, GLuint v) { ProgramUniform1ui(p.id(), p.location(name), v); }
void setUniform(const Program& p, const char* name, double v) { ProgramUniform1d(p.id(), p.location(name), v); }
void setUniform(const Program& p, const char* name, const glm::dvec2& v) {
  ProgramUniform2d(p.id(), p.location(name), v.x, v.y);
}
void setUniform(const Program& p, const char* name, std::span<const float> v) {
  ProgramUniform1fv(p.id(), p.location(name), GLsizei(v.size()), v.data());
}
void setUniform(const Program& p, const char* name, float v) {
  ProgramUniform1f(p.id(), p.location(name), v);
}
void setUniform(const Program& p, const char* name, const glm::vec2& v) {
  ProgramUniform2f(p.id(), p.location(name), v.x, v.y);
}
void setUniform(const Program& p, const char* name, const glm::vec3& v) {
  ProgramUniform3f(p.id(), p.location(name), v.x, v.y, v.z);
}
void setUniform(const Program& p, const char* name, const glm::vec4& v) {
  ProgramUniform4f(p.id(), p.location(name), v.x, v.y, v.z, v.w);
}
void setUniform(const Program& p, const char* name, const glm::mat3& v) {
  ProgramUniformMatrix3fv(p.id(), p.location(name), 1, GL_FALSE, glm::value_ptr(v));
}
void setUniform(const Program& p, const char* name, const glm::mat4& v) {
  ProgramUniformMatrix4fv(p.id(), p.location(name), 1, GL_FALSE,
                          glm::value_ptr(v));
}

}  // namespace mvr::gl
