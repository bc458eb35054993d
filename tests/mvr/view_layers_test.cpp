// ViewLayersSink (mvr live's GPU path): views and EPIs uploaded into a 2D
// array texture land where an EPI volume in host memory holds them (the
// EPI-volume layout), or where the views lie one under another (the
// view-array layout); it lends its texture only for its own layout, size
// and 8-bit types; frames of another size are errors.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "mvr/error.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/gl/view_layers.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

class ViewLayers : public test::GlTest {
 protected:
  static constexpr int kWidth = 5, kViews = 3, kScanlines = 4;
  gl::Texture texture(ViewLayout layout) const {
    gl::Texture t(GL_TEXTURE_2D_ARRAY);
    if (layout == ViewLayout::EpiVolume)
      gl::TextureStorage3D(t.id(), 1, GL_RGBA8, kWidth, kViews, kScanlines);
    else
      gl::TextureStorage3D(t.id(), 1, GL_RGBA8, kWidth, kScanlines, kViews);
    return t;
  }
  Image random(int width, int height) {
    Image image(width, height, PixelType::Srgb8);
    for (uint8_t& b : image.bytes) b = uint8_t(random_());
    return image;
  }
  static ImageBytes texels(const gl::Texture& t) {
    ImageBytes bytes(size_t(kWidth) * kViews * kScanlines * 4);
    gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl::GetTextureImage(t.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()), bytes.data());
    return bytes;
  }
  // An EPI volume's bytes as a view array holds them: layer v, row s is
  // EPI s's row v.
  static ImageBytes asViewArray(const Image& volume) {
    ImageBytes out(volume.bytes.size());
    for (int v = 0; v < kViews; ++v)
      for (int s = 0; s < kScanlines; ++s)
        std::memcpy(out.data() + (size_t(v) * kScanlines + s) * volume.rowBytes(), volume.row(s * kViews + v),
                    volume.rowBytes());
    return out;
  }
  std::mt19937 random_{7};
};

TEST_F(ViewLayers, ViewsAndEpisLandWhereTheLayoutHoldsThem) {
  for (const ViewLayout layout : {ViewLayout::EpiVolume, ViewLayout::ViewArray}) {
    const gl::Texture t = texture(layout);
    ViewLayersSink layers(t.id(), layout, kWidth, kViews, kScanlines);
    EpiVolumeSink volume(kWidth, kScanlines, kViews, PixelType::Srgb8);
    auto expected = [&] {
      return layout == ViewLayout::EpiVolume ? volume.volume().bytes : asViewArray(volume.volume());
    };
    for (int v = 0; v < kViews; ++v) {
      const Image view = random(kWidth, kScanlines);
      layers.putView(0, v, view);
      volume.putView(0, v, view);
    }
    EXPECT_EQ(texels(t), expected());
    const Image epi = random(kWidth, kViews);
    layers.putEpi(0, 2, epi);
    volume.putEpi(0, 2, epi);
    EXPECT_EQ(texels(t), expected());
    EXPECT_EQ(layers.uploads(), kViews + 1);
  }
}

TEST_F(ViewLayers, LendsItsTextureForItsOwnLayoutSizeAndBytesOnly) {
  const gl::Texture volume = texture(ViewLayout::EpiVolume), array = texture(ViewLayout::ViewArray);
  ViewLayersSink epis(volume.id(), ViewLayout::EpiVolume, kWidth, kViews, kScanlines);
  ViewLayersSink views(array.id(), ViewLayout::ViewArray, kWidth, kViews, kScanlines);
  EXPECT_EQ(epis.epiTexture(0, kWidth, kViews, PixelType::Srgb8), volume.id());
  EXPECT_EQ(epis.epiTexture(0, kWidth, kViews, PixelType::F32), 0u);
  EXPECT_EQ(epis.epiTexture(0, kWidth + 1, kViews, PixelType::Srgb8), 0u);
  EXPECT_EQ(epis.epiTexture(1, kWidth, kViews, PixelType::Srgb8), 0u);
  EXPECT_EQ(epis.viewTexture(0, kWidth, kScanlines, kViews, PixelType::Srgb8), 0u);
  EXPECT_EQ(views.viewTexture(0, kWidth, kScanlines, kViews, PixelType::Srgb8), array.id());
  EXPECT_EQ(views.viewTexture(0, kWidth, kScanlines + 1, kViews, PixelType::Srgb8), 0u);
  EXPECT_EQ(views.viewTexture(0, kWidth, kScanlines, kViews, PixelType::F32), 0u);
  EXPECT_EQ(views.epiTexture(0, kWidth, kViews, PixelType::Srgb8), 0u);
}

TEST_F(ViewLayers, FramesOfAnotherSizeAreErrors) {
  const gl::Texture t = texture(ViewLayout::EpiVolume);
  ViewLayersSink layers(t.id(), ViewLayout::EpiVolume, kWidth, kViews, kScanlines);
  EXPECT_THROW(layers.putEpi(0, 0, random(kWidth + 1, kViews)), Error);
  EXPECT_THROW(layers.putEpi(0, kScanlines, random(kWidth, kViews)), Error);
  EXPECT_THROW(layers.putView(0, 0, random(kWidth, kScanlines - 1)), Error);
  EXPECT_THROW(layers.putView(0, kViews, random(kWidth, kScanlines)), Error);
  EXPECT_EQ(layers.uploads(), 0);
  EXPECT_THROW(ViewLayersSink(t.id(), ViewLayout::Quilt, kWidth, kViews, kScanlines), Error);
}

}  // namespace
}  // namespace mvr
