#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <vector>

#include "epi/epi_stream.h"
#include "mvr/error.h"
#include "mvr/io/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(EpiStream, ReorderedStreamIsByteIdenticalToViewImages) {
  test::sharedContext();
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 48, 36, 6);
  auto mvr = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8);
  std::stringstream buffer;
  EpiStreamWriter writer(buffer, {48, 36, 6, 1, 4, 1});
  RenderStats stats;
  mvr->render(cam, writer, stats);
  writer.finish();
  EXPECT_EQ(writer.episWritten(), 36u);
  EXPECT_EQ(buffer.str().size(), 64u + 36u * (8u + 48u * 6u * 4u));

  test::CaptureSink views = test::renderViews(*mvr, cam);
  EpiStreamReader reader(buffer);
  EXPECT_EQ(reader.header().views, 6u);
  int frames = 0;
  while (auto f = reader.next()) {
    EXPECT_EQ(f->scanline, frames);
    for (int i = 0; i < 6; ++i)
      ASSERT_EQ(0, std::memcmp(f->epi.row(i), views.views.at({0, i}).row(f->scanline), 48 * 4));
    ++frames;
  }
  EXPECT_EQ(frames, 36);
}

TEST(EpiStream, BadAndTruncatedStreamsAreErrors) {
  std::stringstream junk("not a stream at all, certainly not sixty-four bytes of header.......");
  EXPECT_THROW(EpiStreamReader r(junk), Error);
  std::stringstream s;
  {
    EpiStreamWriter w(s, {4, 2, 3, 1, 4, 1});
    w.putEpi(0, 0, Image(4, 3, PixelType::U8));
    EXPECT_THROW(w.putEpi(0, 1, Image(5, 3, PixelType::U8)), Error);
  }
  std::string cut = s.str().substr(0, s.str().size() - 5);
  std::stringstream truncated(cut);
  EpiStreamReader r(truncated);
  EXPECT_THROW(r.next(), Error);
}

// A complete stream of `count` EPIs of 4 x 3 (height 2, one row), with the
// given tags.
std::string streamOf(const std::vector<std::pair<int, int>>& tags) {
  std::stringstream s;
  EpiStreamWriter w(s, {4, 2, 3, 1, 4, 1});
  for (auto [row, scanline] : tags) w.putEpi(row, scanline, Image(4, 3, PixelType::U8));
  w.finish();
  return s.str();
}

std::string errorOf(const std::string& bytes) {
  std::stringstream in(bytes);
  try {
    EpiStreamReader r(in);
    while (r.next()) {
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Header fields beyond the renderer's limits (what crashed mvr-consume
// with bad_alloc and length_error), EPIs out of order, bytes after the
// last EPI, and a stream that stops between EPIs: one-line errors.
TEST(EpiStream, HostileStreamsAreOneLineErrors) {
  const std::string good = streamOf({{0, 0}, {0, 1}});
  EXPECT_EQ(errorOf(good), "");
  auto withField = [&](int offset, uint32_t value) {
    std::string bytes = good;
    for (int k = 0; k < 4; ++k) bytes[offset + k] = char((value >> (8 * k)) & 0xFF);
    return bytes;
  };
  EXPECT_NE(errorOf(withField(12, 0x7fffffffu)).find("width 2147483647 exceeds 16384"), std::string::npos);
  EXPECT_NE(errorOf(withField(16, 0xffffffffu)).find("height"), std::string::npos);
  EXPECT_NE(errorOf(withField(20, 0xffffffffu)).find("views"), std::string::npos);
  EXPECT_NE(errorOf(withField(24, 0xffffffffu)).find("rows"), std::string::npos);
  EXPECT_NE(errorOf(withField(24, 0)).find("no valid EPI"), std::string::npos);
  EXPECT_NE(errorOf(withField(36, 2)).find("header color encoding 2 is not 0 (linear) or 1 (sRGB bytes)"),
            std::string::npos);
  EXPECT_EQ(errorOf(withField(36, 1)), "");  // sRGB bytes
  EXPECT_NE(errorOf(streamOf({{0, 1}, {0, 0}})).find("EPI 0 is tagged row 0 scanline 1, expected row 0 scanline 0"),
            std::string::npos);
  EXPECT_NE(errorOf(good + "x").find("data after the last of 2 EPIs"), std::string::npos);
  EXPECT_NE(errorOf(streamOf({{0, 0}})).find("ended after 1 of 2 EPIs"), std::string::npos);
  for (const std::string& e : {errorOf(good + "xyz"), errorOf(withField(16, 0xffffffffu))})
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

}  // namespace
}  // namespace mvr
