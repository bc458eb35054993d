#include <gtest/gtest.h>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

TEST(GlProgram, CompileErrorNamesTheShaderOnOneLine) {
  test::sharedContext();
  try {
    gl::linkProgram("broken-demo", {{GL_VERTEX_SHADER, gl::glslHeader() + "void main() { oops; }"}});
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("shader 'broken-demo' (vertex)"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(GlProgram, HandlesAreMoveOnlyAndRelease) {
  test::sharedContext();
  gl::Buffer a = gl::Buffer::create();
  const GLuint id = a.id();
  EXPECT_NE(id, 0u);
  gl::Buffer b = std::move(a);
  EXPECT_EQ(a.id(), 0u);
  EXPECT_EQ(b.id(), id);
  static_assert(!std::is_copy_constructible_v<gl::Buffer>);
}

}  // namespace
}  // namespace mvr
