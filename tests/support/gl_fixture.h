#pragma once
// One headless GL context per test program (EGL, else OSMesa), created on
// first use: context creation is slow on llvmpipe.
#include <gtest/gtest.h>

#include <memory>

#include "mvr/gl/gl_context.h"
#include "mvr/progress.h"

namespace mvr::test {

inline GlContext& sharedContext() {
  static std::unique_ptr<GlContext> ctx = [] {
    setProgressEnabled(false);
    return GlContext::create(GlPlatform::Auto);
  }();
  return *ctx;
}

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override { sharedContext(); }
};

inline std::string assetPath(const std::string& name) { return std::string(MVR_TEST_ASSETS) + "/" + name; }

}  // namespace mvr::test
