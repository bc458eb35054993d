#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include <cmath>
#include <filesystem>

#include "mvr/error.h"
#include "mvr/images/compare.h"
#include "mvr/images/image_set.h"

#include <nlohmann/json.hpp>

namespace mvr {
namespace {

namespace fs = std::filesystem;

Image gradient(int w, int h, int bump) {
  Image img(w, h, PixelType::U8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.row(y) + x * 4;
      p[0] = uint8_t(x * 7 + bump * (x == 3 && y == 2));
      p[1] = uint8_t(y * 11);
      p[2] = 100;
      p[3] = 255;
    }
  return img;
}

// The layout of a set of `views` views of w x 6 pixels.
Manifest layout(int views, int w = 8) {
  Manifest m;
  m.views = views;
  m.width = w;
  m.height = 6;
  return m;
}

fs::path makeSet(const std::string& name, int bump, int w = 8) {
  fs::path dir = fs::temp_directory_path() / ("mvr_compare_" + name);
  fs::remove_all(dir);
  ImageSetWriter writer(dir.string(), layout(2, w));
  writer.putView(0, 0, gradient(w, 6, 0));
  writer.putView(0, 1, gradient(w, 6, bump));
  writer.manifest().info["test"] = true;
  writer.commit();
  return dir;
}

TEST(Compare, IdenticalSetsAreIdentical) {
  auto d = compareSets(makeSet("a", 0).string(), makeSet("b", 0).string());
  ASSERT_EQ(d.size(), 2u);
  for (const auto& x : d) {
    EXPECT_TRUE(std::isinf(x.psnr));
    EXPECT_EQ(x.identicalFraction, 1.0);
    EXPECT_EQ(x.maxError, 0.0);
  }
}

TEST(Compare, OneChangedPixelIsCountedAndMeasured) {
  auto d = compareSets(makeSet("c", 0).string(), makeSet("d", 51).string());
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[1].name, "view_0001.png");
  EXPECT_EQ(d[1].differingPixels, 1);
  EXPECT_NEAR(d[1].identicalFraction, 47.0 / 48.0, 1e-12);
  EXPECT_NEAR(d[1].maxError, 0.2, 1e-6);
  // MSE = 0.2^2 / (3 * 48) -> PSNR = 10 log10(144 / 0.04)
  EXPECT_NEAR(d[1].psnr, 10 * std::log10(144 / 0.04), 1e-3);
}

Image flat(int w, int h, float grey, float alpha = 1.0f) {
  Image img(w, h, PixelType::F32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = reinterpret_cast<float*>(img.row(y)) + 4 * x;
      p[0] = p[1] = p[2] = grey, p[3] = alpha;
    }
  return img;
}

TEST(Compare, SsimOfFlatImagesIsTheLuminanceTerm) {
  // No variance: SSIM = (2 a b + C1) / (a^2 + b^2 + C1).
  EXPECT_NEAR(ssim(flat(16, 12, 0.5f), flat(16, 12, 0.5f)), 1.0, 1e-12);
  EXPECT_NEAR(ssim(flat(16, 12, 0.5f), flat(16, 12, 0.25f)), 0.2501 / 0.3126, 1e-9);
  // Structure lost: a red checkerboard against the grey of its mean luma.
  Image checker = flat(16, 12, 0.0f);
  for (int y = 0; y < 12; ++y)
    for (int x = (y & 1); x < 16; x += 2) reinterpret_cast<float*>(checker.row(y))[4 * x] = 1.0f;
  EXPECT_LT(ssim(checker, flat(16, 12, 0.299f * 0.5f)), 0.1);
  EXPECT_THROW(ssim(flat(4, 4, 0), flat(4, 5, 0)), Error);
}

TEST(Compare, ColourCountsAsItShowsOverBlack) {
  // Straight alpha: a grey at half alpha shows half its linear value; an
  // empty pixel's stored colour does not show at all.
  const ImageDifference half = compareImages(flat(4, 3, 0.8f, 0.5f), flat(4, 3, 0.4f));
  EXPECT_EQ(half.psnr, INFINITY);  // colour: 0.8 x 0.5 = 0.4
  EXPECT_NEAR(half.maxError, 0.5, 1e-6);  // alpha differs
  EXPECT_EQ(compareImages(flat(4, 3, 0.7f, 0.0f), flat(4, 3, 0.0f, 0.0f)).psnr, INFINITY);
  // The same in sRGB bytes: decoded, weighted, encoded again.
  Image a(1, 1, PixelType::Srgb8), b(1, 1, PixelType::Srgb8);
  a.setLinear(0, 0, glm::vec4(0.8f, 0.8f, 0.8f, 0.5f));
  b.setLinear(0, 0, glm::vec4(0.4f, 0.4f, 0.4f, 1.0f));
  EXPECT_GE(compareImages(a, b).psnr, 48.0);  // within an 8-bit step
  EXPECT_GT(compareImages(a, flat(1, 1, 0.0f)).maxError, 0.6);  // 0.4 linear is 0.66 encoded
}

TEST(Compare, HolesAndExtrasComeFromCoverage) {
  Image a = flat(4, 3, 0.5f), b = flat(4, 3, 0.5f);
  reinterpret_cast<float*>(b.row(1))[4 * 2 + 3] = 0.0f;  // b leaves (2, 1) empty
  reinterpret_cast<float*>(b.row(2))[4 * 0 + 3] = 0.0f;
  reinterpret_cast<float*>(a.row(0))[4 * 3 + 3] = 0.0f;  // a leaves (3, 0) empty
  const ImageDifference d = compareImages(a, b);
  EXPECT_EQ(d.holes, 2);
  EXPECT_EQ(d.extras, 1);
}

TEST(Compare, SizeMismatchIsAnError) {
  EXPECT_THROW(compareSets(makeSet("e", 0).string(), makeSet("f", 0, 9).string()), Error);
}

TEST(Compare, MissingFolderIsAnError) {
  EXPECT_THROW(compareSets("/nonexistent/a", makeSet("g", 0).string()), Error);
}

TEST(ImageSetWriter, UncommittedSetIsRemoved) {
  fs::path dir = fs::temp_directory_path() / "mvr_uncommitted";
  fs::remove_all(dir);
  {
    ImageSetWriter writer(dir.string(), layout(2));
    writer.putView(0, 0, gradient(8, 6, 0));
    writer.flush();
    EXPECT_TRUE(fs::exists(dir / "view_0000.png"));
    writer.putView(0, 1, gradient(8, 6, 1));  // still being encoded when the writer goes
  }
  EXPECT_FALSE(fs::exists(dir / "view_0001.png"));
  EXPECT_FALSE(fs::exists(dir / "view_0000.png"));
  EXPECT_FALSE(fs::exists(dir / "manifest.json"));
}

// An image that cannot be written (a folder in the way of its file)
// fails the set at commit: no manifest, the other files removed.
TEST(ImageSetWriter, AFailedEncodeFailsTheCommit) {
  fs::path dir = fs::temp_directory_path() / "mvr_failed_encode";
  fs::remove_all(dir);
  fs::create_directories(dir / "view_0001.png");
  {
    ImageSetWriter writer(dir.string(), layout(3));
    writer.putView(0, 0, gradient(8, 6, 0));
    writer.putView(0, 1, gradient(8, 6, 1));
    writer.putView(0, 2, gradient(8, 6, 2));
    EXPECT_THROW(writer.commit(), Error);
  }
  EXPECT_FALSE(fs::exists(dir / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "view_0000.png"));
  EXPECT_FALSE(fs::exists(dir / "view_0002.png"));
  fs::remove_all(dir);
}

// A folder that cannot be written is found before any rendering, with the
// operating system's reason; so is a file where the folder should be.
TEST(ImageSetWriter, AnUnwritableFolderFailsAtOnceWithTheReason) {
  const fs::path dir = fs::temp_directory_path() / "mvr_read_only_set";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  const bool enforced = ::access(dir.c_str(), W_OK) != 0;  // root may write anyway
  if (enforced) {
    try {
      ImageSetWriter writer(dir.string(), layout(2));
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("cannot write into the output folder: Permission denied"),
                std::string::npos) << e.what();
    }
  }
  fs::permissions(dir, fs::perms::owner_all);
  fs::remove_all(dir);
  std::ofstream(dir.string()) << "a file";
  try {
    ImageSetWriter writer(dir.string(), layout(2));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create output folder"), std::string::npos) << e.what();
  }
  fs::remove(dir);
}

TEST(ImageSetWriter, NamesGrowDigitsWithTheViewCount) {
  auto names = [](int views, int rows, int height, const std::string& format) {
    Manifest m;
    m.views = views, m.rows = rows, m.height = height, m.format = format;
    return m;
  };
  EXPECT_EQ(names(100, 1, 6, "png").viewName(0, 7), "view_0007.png");
  EXPECT_EQ(names(20000, 1, 6, "png").viewName(0, 7), "view_00007.png");
  EXPECT_EQ(names(100, 3, 6, "exr").viewName(2, 7), "view_r002_c0007.exr");
  EXPECT_EQ(names(1, 1, 480, "png").epiName(0, 12), "epi_0012.png");
}

}  // namespace
}  // namespace mvr
