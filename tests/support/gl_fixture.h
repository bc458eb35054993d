#pragma once
// One headless GL context per test program (EGL, else OSMesa), created on
// first use: context creation is slow on llvmpipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "mvr/gl/gl_api.h"
#include "mvr/gl/gl_context.h"
#include "mvr/frames/progress.h"

namespace mvr::test {

// MVR_TEST_GL=egl|osmesa|auto picks the platform (scripts/gpu-tests forces
// EGL on GPU machines).
inline GlContext& sharedContext() {
  static std::unique_ptr<GlContext> ctx = [] {
    setProgressEnabled(false);
    const char* platform = std::getenv("MVR_TEST_GL");
    return GlContext::create(platform ? parseGlPlatform(platform) : GlPlatform::Auto);
  }();
  return *ctx;
}

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override { sharedContext(); }
};

// The assets folder: MVR_TEST_ASSETS from the environment (a packed copy on
// another machine), else the checkout's, compiled in.
inline std::string assetsDir() {
  const char* dir = std::getenv("MVR_TEST_ASSETS");
  return dir ? dir : MVR_TEST_ASSETS;
}
inline std::string assetPath(const std::string& name) { return assetsDir() + "/" + name; }
// A file of the checkout: MVR_TEST_SOURCE from the environment (the
// checkout on another machine), else the one compiled in.
inline std::string sourcePath(const std::string& relative) {
  const char* dir = std::getenv("MVR_TEST_SOURCE");
  return std::string(dir ? dir : MVR_TEST_SOURCE) + "/" + relative;
}

// A count of decisions a GPU pass makes from double-precision divisions
// against the host's: GLSL promises double division no better than single
// precision (GLSL 4.60, 4.7.1), and a GPU's is a reciprocal refined by
// Newton steps, while llvmpipe's is the CPU's, correctly rounded. Where a
// value lies within an ulp of a boundary a GPU may decide it the other
// way. So: exactly the host's count where GL runs on the CPU, and
// elsewhere all but one in a thousand of `decisions` (at least 2).
inline void expectSameDecisions(long got, long want, long decisions, const std::string& label) {
  if (gl::rendersOnCpu()) {
    EXPECT_EQ(got, want) << label;
    return;
  }
  EXPECT_LE(std::abs(got - want), std::max<long>(2, decisions / 1000)) << label << ": " << got << " against " << want;
}

// The first `count` elements of a GL buffer, read back.
template <class T>
std::vector<T> download(GLuint buffer, size_t count) {
  std::vector<T> out(count);
  if (count) gl::GetNamedBufferSubData(buffer, 0, GLsizeiptr(count * sizeof(T)), out.data());
  return out;
}

}  // namespace mvr::test
