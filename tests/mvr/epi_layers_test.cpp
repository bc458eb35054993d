// EpiLayersSink (mvr live's GPU path): views and EPIs uploaded into a 2D
// array texture land where an EPI volume in host memory holds them (layer
// s scanline s's EPI, row v view v's); it lends its texture only for its
// own size and 8-bit types; frames of another size are errors.
#include <gtest/gtest.h>

#include <random>

#include "mvr/error.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/gl/epi_layers.h"
#include "mvr/gl/gl_handles.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

class EpiLayers : public test::GlTest {
 protected:
  static constexpr int kWidth = 5, kViews = 3, kScanlines = 4;
  void SetUp() override {
    GlTest::SetUp();
    texture_ = gl::Texture(GL_TEXTURE_2D_ARRAY);
    gl::TextureStorage3D(texture_.id(), 1, GL_RGBA8, kWidth, kViews, kScanlines);
  }
  Image random(int width, int height) {
    Image image(width, height, PixelType::Srgb8);
    for (uint8_t& b : image.bytes) b = uint8_t(random_());
    return image;
  }
  std::vector<uint8_t> texels() const {
    std::vector<uint8_t> bytes(size_t(kWidth) * kViews * kScanlines * 4);
    gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl::GetTextureImage(texture_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
    return bytes;
  }
  gl::Texture texture_;
  std::mt19937 random_{7};
};

TEST_F(EpiLayers, ViewsAndEpisLandWhereAnEpiVolumeHoldsThem) {
  EpiLayersSink layers(texture_.id(), kWidth, kViews, kScanlines);
  EpiVolumeSink volume(kWidth, kScanlines, kViews, PixelType::Srgb8);
  for (int v = 0; v < kViews; ++v) {
    const Image view = random(kWidth, kScanlines);
    layers.putView(0, v, view);
    volume.putView(0, v, view);
  }
  EXPECT_EQ(texels(), volume.volume().bytes);
  const Image epi = random(kWidth, kViews);
  layers.putEpi(0, 2, epi);
  volume.putEpi(0, 2, epi);
  EXPECT_EQ(texels(), volume.volume().bytes);
  EXPECT_EQ(layers.uploads(), kViews + 1);
}

TEST_F(EpiLayers, LendsItsTextureForItsOwnSizeAndBytesOnly) {
  EpiLayersSink layers(texture_.id(), kWidth, kViews, kScanlines);
  EXPECT_EQ(layers.epiTexture(0, kWidth, kViews, PixelType::Srgb8), texture_.id());
  EXPECT_EQ(layers.epiTexture(0, kWidth, kViews, PixelType::F32), 0u);
  EXPECT_EQ(layers.epiTexture(0, kWidth + 1, kViews, PixelType::Srgb8), 0u);
  EXPECT_EQ(layers.epiTexture(1, kWidth, kViews, PixelType::Srgb8), 0u);
}

TEST_F(EpiLayers, FramesOfAnotherSizeAreErrors) {
  EpiLayersSink layers(texture_.id(), kWidth, kViews, kScanlines);
  EXPECT_THROW(layers.putEpi(0, 0, random(kWidth + 1, kViews)), Error);
  EXPECT_THROW(layers.putEpi(0, kScanlines, random(kWidth, kViews)), Error);
  EXPECT_THROW(layers.putView(0, 0, random(kWidth, kScanlines - 1)), Error);
  EXPECT_THROW(layers.putView(0, kViews, random(kWidth, kScanlines)), Error);
  EXPECT_EQ(layers.uploads(), 0);
}

}  // namespace
}  // namespace mvr
