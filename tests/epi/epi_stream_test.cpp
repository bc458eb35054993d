#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

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

}  // namespace
}  // namespace mvr
