// Views encoded straight from EPIs (mvr/frames/png_views.h): the files must be
// the bytes ImageSetWriter writes for the same views, whatever order the
// EPIs come in, and a render that ends early must not pass for complete.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <random>

#include "mvr/error.h"
#include "mvr/frames/png_views.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

std::vector<unsigned char> fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

Manifest manifestFor(int width, int height, int views, int rows, int level, int bits = 8, bool srgb = true) {
  return {.views = views, .rows = rows, .width = width, .height = height, .bits = bits, .compression = level,
          .srgb = srgb};
}

// EPIs with runs (so the files deflate) and noise; epis[row][scanline].
// Floats run a little beyond [0, 1] at both ends (the clamps).
std::vector<std::vector<Image>> makeEpis(int width, int height, int views, int rows, PixelType type) {
  std::mt19937 rng(11);
  std::vector<std::vector<Image>> epis(static_cast<size_t>(rows));
  for (auto& row : epis)
    for (int j = 0; j < height; ++j) {
      Image epi(width, views, type);
      for (int i = 0; i < views; ++i)
        for (int x = 0; x < width * 4; ++x) {
          const uint8_t b = uint8_t(x < width * 2 ? (x / 4 + i + j) : rng());
          if (type == PixelType::F32)
            reinterpret_cast<float*>(epi.row(i))[x] = float(b) / 250.0f - 0.01f + float(rng() % 1000) * 1e-7f;
          else
            epi.row(i)[x] = b;
        }
      row.push_back(std::move(epi));
    }
  return epis;
}

// 2 rows of 40 views of 301 x 90: 3 PNG segments a view. The views
// through ImageSetWriter::putView (transposed here by hand) and straight
// from the EPIs, in order (copied) and shuffled within each row (handed
// over in place): the same files. Byte EPIs into 8-bit files; float ones
// into 16-bit files, sRGB and linear, and into 8-bit ones.
TEST(EpisToPngViews, FilesAreThoseOfTheViews) {
  const int width = 301, height = 90, views = 40, rows = 2;
  struct Case {
    PixelType type;
    int bits;
    bool srgb;
  };
  for (const Case c : {Case{PixelType::Srgb8, 8, true}, Case{PixelType::U8, 8, true}, Case{PixelType::F32, 16, true},
                       Case{PixelType::F32, 16, false}, Case{PixelType::F32, 8, true}}) {
    const PixelType type = c.type;
    const std::string label = std::string(type == PixelType::F32 ? "float" : type == PixelType::U8 ? "linear" : "sRGB") +
                              " into " + std::to_string(c.bits) + " bits" + (c.srgb ? "" : ", linear file");
    const Manifest manifest = manifestFor(width, height, views, rows, 1, c.bits, c.srgb);
    const auto epis = makeEpis(width, height, views, rows, type);
    const fs::path expected = test::freshDir("pngviews_expected");
    {
      ImageSetWriter writer(expected.string(), manifest);
      for (int r = 0; r < rows; ++r)
        for (int i = 0; i < views; ++i) {
          Image view(width, height, type);
          for (int j = 0; j < height; ++j) std::copy_n(epis[size_t(r)][size_t(j)].row(i), view.rowBytes(), view.row(j));
          writer.putView(r, i, view);
        }
      writer.commit();
    }
    // Unbounded, in order and shuffled; with a budget for the files'
    // bytes that sends them to disk after every EPI, and one that does so
    // now and then.
    for (const auto& [shuffled, budget] : {std::pair{false, SIZE_MAX}, std::pair{true, SIZE_MAX},
                                           std::pair{true, size_t(1)}, std::pair{false, size_t(60000)}}) {
      const fs::path got = test::freshDir("pngviews_got");
      ImageSetWriter writer(got.string(), manifest);
      EpisToPngViews sink(writer, type, budget);
      std::mt19937 rng(5);
      for (int r = 0; r < rows; ++r) {
        std::vector<int> order(static_cast<size_t>(height));
        for (int j = 0; j < height; ++j) order[size_t(j)] = j;
        if (shuffled) std::shuffle(order.begin(), order.end(), rng);
        for (int j : order) {
          if (!shuffled) {
            sink.putEpi(r, j, epis[size_t(r)][size_t(j)]);
            continue;
          }
          // Handed over in place: the sink takes the pixels and leaves an
          // image of the same shape.
          Image epi = epis[size_t(r)][size_t(j)];
          sink.putEpiInPlace(r, j, epi);
          EXPECT_TRUE(epi.width == width && epi.height == views && epi.type == type);
        }
      }
      sink.finish();
      writer.commit();
      EXPECT_EQ(writer.filesWritten(), size_t(views * rows));
      // The files grow by a deflated segment (a few a view) at a time.
      if (budget != SIZE_MAX) {
        EXPECT_GE(sink.spills(), budget == 1 ? 2 * rows : 2);
      } else {
        EXPECT_EQ(sink.spills(), 0);
      }
      EXPECT_EQ(std::distance(fs::directory_iterator(got), {}), views * rows + 1) << "the views and the manifest";
      for (int r = 0; r < rows; ++r)
        for (int i = 0; i < views; ++i) {
          const std::string name = writer.manifest().viewName(r, i);
          ASSERT_TRUE(fs::exists(got / name)) << name;
          EXPECT_EQ(fileBytes(got / name), fileBytes(expected / name))
              << name << (shuffled ? ", shuffled" : "") << ", " << label << ", budget " << budget;
        }
    }
  }
}

// A render that stops within a row leaves none of the row's bytes already
// on disk behind: no temporary file, no view.
TEST(EpisToPngViews, AnUnfinishedRowLeavesNoFiles) {
  const fs::path dir = test::freshDir("pngviews_unfinished");
  const auto epis = makeEpis(64, 20, 6, 1, PixelType::Srgb8);
  {
    ImageSetWriter writer(dir.string(), manifestFor(64, 20, 6, 1, 1));
    EpisToPngViews sink(writer, PixelType::Srgb8, 1);
    for (int j = 0; j < 12; ++j) sink.putEpi(0, j, epis[0][size_t(j)]);
    ASSERT_GE(sink.spills(), 1);
    EXPECT_TRUE(fs::exists(dir / (writer.manifest().viewName(0, 3) + ".part")));
  }
  for (const auto& entry : fs::directory_iterator(dir)) ADD_FAILURE() << entry.path() << " is left";
}

// Rows are encoded on the pool: a failure there (here the folder gone
// when the files' bytes go to disk) surfaces at a later put or at finish.
TEST(EpisToPngViews, AnEncodingErrorSurfaces) {
  const fs::path dir = test::freshDir("pngviews_failing");
  const auto epis = makeEpis(64, 20, 6, 1, PixelType::Srgb8);
  ImageSetWriter writer(dir.string(), manifestFor(64, 20, 6, 1, 1));
  EpisToPngViews sink(writer, PixelType::Srgb8, 1);
  fs::remove_all(dir);
  try {
    for (int j = 0; j < 20; ++j) sink.putEpi(0, j, epis[0][size_t(j)]);
    sink.finish();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pngviews_failing"), std::string::npos) << e.what();
  }
}

TEST(EpisToPngViews, MisuseIsAnError) {
  const fs::path dir = test::freshDir("pngviews_errors");
  ImageSetWriter writer(dir.string(), manifestFor(8, 4, 3, 2, 1));
  {
    // Bytes into 16-bit files are not stored as they are: the volume's way.
    ImageSetWriter deep(test::freshDir("pngviews_errors16").string(), manifestFor(8, 4, 3, 2, 1, 16));
    EXPECT_FALSE(EpisToPngViews::handles(deep.manifest(), PixelType::U8));
    EXPECT_TRUE(EpisToPngViews::handles(deep.manifest(), PixelType::F32));
    EXPECT_THROW(EpisToPngViews(deep, PixelType::Srgb8), Error);
  }
  EpisToPngViews sink(writer, PixelType::Srgb8);
  const Image epi(8, 3, PixelType::Srgb8);
  EXPECT_THROW(sink.putEpi(0, 0, Image(8, 2, PixelType::Srgb8)), Error) << "views";
  EXPECT_THROW(sink.putEpi(0, 0, Image(8, 3, PixelType::U8)), Error) << "type";
  EXPECT_THROW(sink.putEpi(0, 4, epi), Error) << "scanline";
  sink.putEpi(0, 0, epi);
  sink.putEpi(0, 2, epi);
  EXPECT_THROW(sink.putEpi(0, 2, epi), Error) << "a scanline twice, early";
  EXPECT_THROW(sink.putEpi(0, 0, epi), Error) << "a scanline twice, done";
  EXPECT_THROW(sink.putEpi(1, 0, epi), Error) << "the next row before this one is done";
  EXPECT_THROW(sink.finish(), Error) << "a row with scanlines missing";
  sink.putEpi(0, 1, epi);  // brings 2 in
  sink.putEpi(0, 3, epi);
  sink.finish();  // the rows are encoded on the pool: handed to the writer once finish returns
  writer.flush();
  EXPECT_EQ(writer.filesWritten(), 3u);
}

}  // namespace
}  // namespace mvr
