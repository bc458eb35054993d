// EPI <-> view reordering, in memory and through the scratch file: the
// scratch path must give the same bytes in the same order (issue 15).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "mvr/frames/volume.h"
#include "mvr/error.h"
#include "tests/support/capture_sink.h"

namespace mvr {
namespace {

Image randomImage(int w, int h, PixelType type, std::mt19937& rng) {
  Image img(w, h, type);
  for (uint8_t& b : img.bytes) b = uint8_t(rng());
  return img;
}

std::string scratchDir() { return std::filesystem::temp_directory_path().string(); }

TEST(FrameTranspose, ViewRowIsEpiScanlineByHand) {
  // 3 EPIs (scanlines) of 2 views, 1 pixel wide: view i's row j is EPI j's row i.
  test::CaptureSink views;
  EpisToViews sink(views, 1, 3, 2, PixelType::U8);
  for (int j = 0; j < 3; ++j) {
    Image epi(1, 2, PixelType::U8);
    for (int i = 0; i < 2; ++i) epi.row(i)[0] = uint8_t(10 * j + i);
    sink.putEpi(0, j, epi);
  }
  ASSERT_EQ(views.views.size(), 2u);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_EQ(views.views[std::pair(0, i)].row(j)[0], 10 * j + i);
}

// Two rows of a 7-scanline, 5-view, 3-pixel volume through EpisToViews
// under a budget of `framesHeld` views; returns what came out.
test::CaptureSink epiToViewsRows(PixelType type, int framesHeld, int* perPass = nullptr,
                                 bool* scratch = nullptr) {
  const int width = 3, height = 7, views = 5;
  const size_t viewBytes = Image(width, height, type).bytes.size();
  test::CaptureSink out;
  EpisToViews sink(out, width, height, views, type,
                   {.budget = framesHeld ? viewBytes * size_t(framesHeld) : 0,
                    .scratchDir = scratchDir()});
  std::mt19937 rng(7);
  for (int row = 0; row < 2; ++row)
    for (int j = 0; j < height; ++j) sink.putEpi(row, j, randomImage(width, views, type, rng));
  if (perPass) *perPass = sink.transpose().outputsPerPass();
  if (scratch) *scratch = sink.transpose().usesScratch();
  return out;
}

TEST(FrameTranspose, ScratchFileGivesTheSameViewsAsMemory) {
  for (PixelType type : {PixelType::U8, PixelType::F32}) {
    const test::CaptureSink memory = epiToViewsRows(type, 0);
    ASSERT_EQ(memory.views.size(), 10u);
    for (int held : {1, 2, 4, 5}) {
      int perPass = 0;
      bool scratch = false;
      const test::CaptureSink bounded = epiToViewsRows(type, held, &perPass, &scratch);
      EXPECT_EQ(scratch, held < 5) << held;  // 5 views fit: no scratch
      EXPECT_EQ(perPass, held);
      ASSERT_EQ(bounded.views.size(), memory.views.size());
      for (const auto& [key, image] : memory.views)
        EXPECT_EQ(bounded.views.at(key).bytes, image.bytes) << "row " << key.first << " view " << key.second;
    }
  }
}

TEST(FrameTranspose, ScratchFileGivesTheSameEpisAsMemory) {
  const int width = 4, height = 6, views = 5;
  std::mt19937 rng(3);
  std::vector<Image> input;
  for (int i = 0; i < views; ++i) input.push_back(randomImage(width, height, PixelType::U8, rng));
  const size_t epiBytes = Image(width, views, PixelType::U8).bytes.size();
  test::CaptureSink memory, bounded;
  ViewsToEpis inMemory(memory, width, height, views, PixelType::U8);
  ViewsToEpis scratch(bounded, width, height, views, PixelType::U8,
                      {.budget = epiBytes * 4, .scratchDir = scratchDir()});
  for (int i = views - 1; i >= 0; --i) {  // any order of views
    inMemory.putView(0, i, input[size_t(i)]);
    scratch.putView(0, i, input[size_t(i)]);
  }
  EXPECT_TRUE(scratch.transpose().usesScratch());
  ASSERT_EQ(memory.epis.size(), size_t(height));
  for (const auto& [key, epi] : memory.epis) EXPECT_EQ(bounded.epis.at(key).bytes, epi.bytes);
  EXPECT_EQ(memory.epis.at(std::pair(0, 2)).row(3)[5], input[3].row(2)[5]);
}

TEST(FrameTranspose, UnwritableScratchFolderNamesTheFolder) {
  test::CaptureSink out;
  try {
    EpisToViews sink(out, 8, 8, 8, PixelType::U8, {.budget = 1, .scratchDir = "/nonexistent/scratch"});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scratch: cannot create a scratch file"),
              std::string::npos)
        << e.what();
  }
}

TEST(FrameTranspose, WrongShapesAreErrors) {
  test::CaptureSink out;
  EpisToViews sink(out, 4, 3, 2, PixelType::U8);
  EXPECT_THROW(sink.putEpi(0, 0, Image(4, 3, PixelType::U8)), Error);
  EXPECT_THROW(sink.putEpi(0, 3, Image(4, 2, PixelType::U8)), Error);
  EXPECT_THROW(sink.putEpi(0, 0, Image(5, 2, PixelType::U8)), Error);
}

}  // namespace
}  // namespace mvr
