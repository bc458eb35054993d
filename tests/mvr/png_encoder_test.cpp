// Our PNG encoder (mvr/images/png_encoder.h) against OpenImageIO, which wrote
// every PNG before it and still reads them: the same pixels, the same tags
// and text, at every level and bit depth, for byte and float images.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/images/adler32.h"
#include "mvr/images/image_codec.h"
#include "mvr/images/image_file.h"
#include "mvr/images/png_encoder.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// Adler-32 by its definition, a byte at a time, reduced every byte.
uint32_t adlerByDefinition(uint32_t adler, const std::vector<uint8_t>& bytes) {
  uint32_t a = adler & 0xffff, b = adler >> 16;
  for (uint8_t v : bytes) a = (a + v) % 65521, b = (b + a) % 65521;
  return b << 16 | a;
}

// The vector path against the definition: every length around its 32-byte
// steps and its reduction blocks, bytes at their largest (the overflow
// case) and random, carried on from a running checksum; RFC 1950's value
// for "Wikipedia".
TEST(Adler32, MatchesTheDefinition) {
  const std::string wiki = "Wikipedia";
  EXPECT_EQ(adler32Update(1, std::span(reinterpret_cast<const uint8_t*>(wiki.data()), wiki.size())), 0x11E60398u);
  uint32_t seed = 7;
  for (size_t n : {0, 1, 31, 32, 33, 63, 64, 100, 16383, 16384, 16385, 50000, 200003}) {
    std::vector<uint8_t> ones(n, 255), noise(n);
    for (uint8_t& v : noise) seed = seed * 1664525u + 1013904223u, v = uint8_t(seed >> 24);
    for (const std::vector<uint8_t>* bytes : {&ones, &noise})
      for (uint32_t start : {1u, 65520u << 16 | 65520u}) {  // none yet; both sums at their largest
        EXPECT_EQ(adler32Update(start, *bytes), adlerByDefinition(start, *bytes))
            << n << " bytes" << (bytes == &ones ? " of 255" : " of noise") << " from " << start;
      }
  }
}

// A pattern with runs, gradients and noise, so every filter wins somewhere.
Image bytePattern(int w, int h, PixelType type) {
  Image img(w, h, type);
  uint32_t seed = 12345;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        seed = seed * 1664525u + 1013904223u;
        const int noise = int(seed >> 28);
        img.row(y)[4 * x + c] = uint8_t(x < w / 3 ? 200 : x < 2 * w / 3 ? x * 3 + y * c : noise * 17);
      }
  return img;
}

// Float samples at and around every rounding edge, out of range, and NaN.
Image floatEdges() {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> values = {-1.0f, -0.0f, 0.0f, 0.5f / 255.0f, 0.49f / 255.0f, 0.51f / 255.0f, 0.5f,
                               127.5f / 255.0f, 1.0f - 1e-7f, 1.0f, 1.5f, 1e30f, nan, 0.5f / 65535.0f, 0.25f};
  for (int i = 0; i < 49; ++i) values.push_back(float(i) / 48.0f);
  Image img(int(values.size()), 2, PixelType::F32);
  float* v = reinterpret_cast<float*>(img.bytes.data());
  for (size_t i = 0; i < values.size() * 8; ++i) v[i] = values[(i / 4 + i % 4 * 7) % values.size()];
  return img;
}

fs::path emptyDir(const std::string& name) {
  const fs::path dir = test::freshDir(name);
  fs::create_directories(dir);
  return dir;
}

std::vector<unsigned char> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Writes through OpenImageIO's encoder (the module), as writeImage did.
void writeWithModule(const Image& pixels, const fs::path& path, const ImageEncoding& e, bool srgb) {
  std::vector<unsigned char> out;
  ASSERT_EQ(imageCodec().encode(pixels, "png", e, srgb, out), "");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
}

// One segment (37 x 23), many (300 x 200: 27 rows a segment, 8 IDAT
// chunks) and rows longer than a segment (17000 wide: a row a segment),
// at every kind of level: stored, fast, filtered.
TEST(PngEncoder, BytesRoundTripAtEveryLevel) {
  const fs::path dir = emptyDir("png_bytes");
  for (PixelType type : {PixelType::U8, PixelType::Srgb8})
    for (const glm::ivec2 size : {glm::ivec2(37, 23), glm::ivec2(300, 200), glm::ivec2(17000, 3)}) {
      const Image img = bytePattern(size.x, size.y, type);
      for (int level : {0, 1, 3, 4, 6, 9}) {
        const std::string what = std::to_string(size.x) + " wide, level " + std::to_string(level);
        const fs::path file = dir / ("l" + std::to_string(level) + ".png");
        writeImage(img, file.string(), {.pngLevel = level});
        const Image back = readImage(file.string());
        EXPECT_EQ(back.type, type) << what << ": the tag says how to read it";
        EXPECT_EQ(back.bytes, img.bytes) << what;
        EXPECT_EQ(readImageEncoding(file.string()).srgb, type == PixelType::Srgb8);
      }
    }
}

// Encoders fed side by side, row by row, on one thread (as views are fed
// from EPIs) write the bytes each writes alone: a file depends on its
// pixels, not on what else was encoded meanwhile.
TEST(PngEncoder, InterleavedEncodersWriteWhatEachWritesAlone) {
  const fs::path dir = emptyDir("png_interleaved");
  for (int level : {1, 6}) {
    const Image a = bytePattern(300, 200, PixelType::Srgb8), b = bytePattern(200, 300, PixelType::Srgb8);
    writeImage(a, (dir / "a.png").string(), {.pngLevel = level});
    writeImage(b, (dir / "b.png").string(), {.pngLevel = level});
    std::vector<unsigned char> outA, outB;
    PngEncoder encA({.width = 300, .height = 200, .level = level}, outA);
    PngEncoder encB({.width = 200, .height = 300, .level = level}, outB);
    for (int y = 0; y < 300; ++y) {
      if (y < 200) encA.addRow({a.row(y), a.rowBytes()});
      encB.addRow({b.row(y), b.rowBytes()});
    }
    ASSERT_TRUE(encA.finished() && encB.finished());
    EXPECT_EQ(outA, fileBytes(dir / "a.png")) << "level " << level;
    EXPECT_EQ(outB, fileBytes(dir / "b.png")) << "level " << level;
  }
}

// The adaptive filters pay off on a gradient: the file is much smaller
// than with no filter at a zlib level as strong (972 bytes at level 4
// against 1878 at level 3).
TEST(PngEncoder, FiltersShrinkGradients) {
  Image img(256, 64, PixelType::U8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 4; ++c) img.row(y)[4 * x + c] = uint8_t(x + 3 * y + 50 * c);
  std::vector<unsigned char> plain, filtered;
  PngEncoder a({256, 64, 8, 3, true}, plain), b({256, 64, 8, 4, true}, filtered);
  for (int y = 0; y < 64; ++y) {
    a.addRow({img.row(y), img.rowBytes()});
    b.addRow({img.row(y), img.rowBytes()});
  }
  ASSERT_TRUE(a.finished() && b.finished());
  EXPECT_LT(filtered.size() * 3, plain.size() * 2);
}

// Float images quantised as OpenImageIO quantised them (round to nearest,
// clamped, NaN to 0), to 8 and 16 bits, tagged sRGB or linear.
TEST(PngEncoder, FloatsQuantisedAsOpenImageIoDid) {
  const fs::path dir = emptyDir("png_floats");
  const Image img = floatEdges();
  for (int bits : {8, 16})
    for (bool srgb : {true, false}) {
      const std::string what = std::to_string(bits) + (srgb ? " bits sRGB" : " bits linear");
      const ImageEncoding e{.bits = bits, .srgb = srgb};
      const fs::path ours = dir / "ours.png", theirs = dir / "theirs.png";
      writeImage(img, ours.string(), e);
      const ImageEncoding stored = readImageEncoding(ours.string());
      EXPECT_EQ(stored.bits, bits) << what;
      EXPECT_EQ(stored.srgb, srgb) << what;
      // The module gets what writeImage quantises: colour sRGB-encoded
      // for an sRGB file, alpha linear.
      Image encoded = img;
      if (srgb) {
        float* v = reinterpret_cast<float*>(encoded.bytes.data());
        for (size_t i = 0; i < size_t(img.width) * img.height * 4; ++i)
          if (i % 4 != 3) v[i] = srgbEncode(v[i]);
      }
      writeWithModule(encoded, theirs, e, srgb);
      EXPECT_EQ(readImage(ours.string()).bytes, readImage(theirs.string()).bytes) << what;
    }
}

// Images hold straight alpha, and so do the files: a half-transparent
// pixel keeps its colour in every format (OpenImageIO had divided a PNG's
// colour by alpha on writing and multiplied it back on reading).
TEST(PngEncoder, StraightAlphaInEveryFormat) {
  const fs::path dir = emptyDir("png_alpha");
  Image img(3, 2, PixelType::F32);
  float* v = reinterpret_cast<float*>(img.bytes.data());
  for (int i = 0; i < 6; ++i) {
    v[4 * i] = v[4 * i + 1] = v[4 * i + 2] = 0.4f;
    v[4 * i + 3] = 0.5f;
  }
  for (const char* name : {"a.png", "a.tif", "a.exr"}) {
    const std::string file = (dir / name).string();
    writeImage(img, file, {.bits = std::string(name) == "a.exr" ? 32 : 8});
    const glm::vec4 p = readImage(file).linear(1, 1);
    EXPECT_NEAR(p.r, 0.4f, 0.01f) << name;
    EXPECT_NEAR(p.a, 0.5f, 0.003f) << name;
  }
}

TEST(PngEncoder, TextChunksReadBack) {
  const fs::path file = emptyDir("png_text") / "quilt.png";
  const std::string json = R"({"LKGAspect":1.33,"LKGColumns":2})";
  writeImage(bytePattern(8, 4, PixelType::Srgb8), file.string(), {.attributes = {{"Exif:UserComment", json}}});
  EXPECT_EQ(readImageAttribute(file.string(), "Exif:UserComment"), json);
}

TEST(PngEncoder, BadInputsAreOneLineErrorsAndLeaveNoFile) {
  const fs::path dir = emptyDir("png_errors"), file = dir / "bad.png";
  const Image img = bytePattern(8, 4, PixelType::U8);
  for (const std::string& key : {std::string(), std::string(80, 'k'), std::string(" lead")}) {
    try {
      writeImage(img, file.string(), {.attributes = {{key, "v"}}});
      ADD_FAILURE() << "key '" << key << "' accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(file.string() + ": "), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(fs::exists(file.string() + ".part"));
  }
  std::vector<unsigned char> out;
  PngEncoder png({8, 1, 8, 1, true}, out);
  const std::vector<uint8_t> row(png.rowBytes());
  EXPECT_THROW(png.addRow(std::span(row).first(row.size() - 1)), Error);
  png.addRow(row);
  EXPECT_THROW(png.addRow(row), Error);
  EXPECT_THROW(PngEncoder({0, 4, 8, 1, true}, out), Error);
  EXPECT_THROW(PngEncoder({4, 4, 12, 1, true}, out), Error);
}

}  // namespace
}  // namespace mvr
