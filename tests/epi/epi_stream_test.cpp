#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <vector>

#include "mvr/frames/epi_stream.h"
#include "mvr/frames/stream_queue.h"
#include "mvr/error.h"
#include "mvr/assets/scene_io.h"
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

// Frames read into one reused buffer (as mvr-consume reads them) hold what
// fresh frames hold, and a cut stream still fails with the buffer at size.
TEST(EpiStream, FramesReadIntoAReusedBufferAreTheFreshOnes) {
  const EpiStreamHeader header{8, 5, 3, 2, 4, 1};
  std::stringstream bytes;
  {
    EpiStreamWriter writer(bytes, header);
    for (int row = 0; row < 2; ++row)
      for (int j = 0; j < 5; ++j) {
        Image epi(8, 3, PixelType::U8);
        for (size_t b = 0; b < epi.bytes.size(); ++b) epi.bytes[b] = uint8_t(b * 5 + j * 17 + row * 101);
        writer.putEpi(row, j, epi);
      }
  }
  std::stringstream a(bytes.str()), b(bytes.str());
  EpiStreamReader fresh(a), reused(b);
  EpiStreamReader::Frame frame{0, 0, Image()};
  int frames = 0;
  while (auto f = fresh.next()) {
    ASSERT_TRUE(reused.next(frame));
    EXPECT_EQ(frame.row, f->row);
    EXPECT_EQ(frame.scanline, f->scanline);
    EXPECT_EQ(frame.epi.bytes, f->epi.bytes) << "EPI " << frames;
    EXPECT_EQ(frame.epi.width, 8);
    EXPECT_EQ(frame.epi.height, 3);
    ++frames;
  }
  EXPECT_FALSE(reused.next(frame));
  EXPECT_EQ(frames, 10);
  std::stringstream cut(bytes.str().substr(0, bytes.str().size() - 7));
  EpiStreamReader short_(cut);
  for (int k = 0; k < 9; ++k) ASSERT_TRUE(short_.next(frame));
  EXPECT_THROW(short_.next(frame), Error);
}

// The queue takes in-place EPIs' pixels and hands the producer a written
// EPI's image back: the stream must hold every EPI as it was handed over,
// and the producer must always get an image of its EPI's size and type.
TEST(EpiStream, TheQueueSendsInPlaceEpisUnchanged) {
  const EpiStreamHeader header{8, 24, 5, 1, 4, 1};
  auto epiOf = [](int scanline) {
    Image epi(8, 5, PixelType::U8);
    for (size_t b = 0; b < epi.bytes.size(); ++b) epi.bytes[b] = uint8_t(b * 7 + scanline * 13);
    return epi;
  };
  std::stringstream direct, queued;
  {
    EpiStreamWriter writer(direct, header);
    for (int j = 0; j < 24; ++j) writer.putEpi(0, j, epiOf(j));
    writer.finish();
  }
  {
    QueuedEpiStream stream(queued, header, 2);
    Image reused;
    for (int j = 0; j < 24; ++j) {
      if (j % 5 == 4) {  // now and then a copy, as a producer without spare images hands over
        stream.putEpi(0, j, epiOf(j));
        continue;
      }
      reused = epiOf(j);
      stream.putEpiInPlace(0, j, reused);
      ASSERT_EQ(reused.width, 8);
      ASSERT_EQ(reused.height, 5);
      ASSERT_EQ(reused.type, PixelType::U8);
      ASSERT_EQ(reused.bytes.size(), size_t(8 * 5 * 4));
    }
    stream.finish();
  }
  EXPECT_EQ(queued.str(), direct.str());
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

// A sequence's frames follow one another, the header saying how many and
// when; each frame's tags start again at row 0, scanline 0. A stream that
// ends inside a frame is an error, and an older header (0 frames) reads
// as a still.
TEST(EpiStream, SequenceFramesFollowOneAnother) {
  EpiStreamHeader h{4, 2, 3, 1, 4, 1};
  h.frames = 3, h.startTime = 0.5, h.frameRate = 24.0;
  std::stringstream s;
  {
    EpiStreamWriter w(s, h);
    for (int k = 0; k < 3; ++k)
      for (int scanline = 0; scanline < 2; ++scanline) {
        Image epi(4, 3, PixelType::U8);
        epi.bytes[0] = uint8_t(10 * k + scanline);
        w.putEpi(0, scanline, epi);
      }
  }
  const std::string bytes = s.str();
  EXPECT_EQ(bytes.size(), 64u + 6u * (8u + 4u * 3u * 4u));
  EXPECT_EQ(h.recordOffset(0, 1, 2), 64u + 5u * (8u + 4u * 3u * 4u));
  std::stringstream in(bytes);
  EpiStreamReader r(in);
  EXPECT_EQ(r.header().frames, 3u);
  EXPECT_EQ(r.header().startTime, 0.5);
  EXPECT_EQ(r.header().frameRate, 24.0);
  int read = 0;
  while (auto f = r.next()) {
    EXPECT_EQ(f->frame, read / 2);
    EXPECT_EQ(f->scanline, read % 2);
    EXPECT_EQ(f->epi.bytes[0], 10 * (read / 2) + read % 2);
    ++read;
  }
  EXPECT_EQ(read, 6);
  EXPECT_NE(errorOf(bytes.substr(0, bytes.size() - (8 + 48))).find("ended after 5 of 6 EPIs"), std::string::npos);
  std::string older = streamOf({{0, 0}, {0, 1}});
  ASSERT_EQ(older[40], 1);  // a still says 1 frame
  older[40] = 0;
  EXPECT_EQ(errorOf(older), "");
  std::string negativeRate = bytes;
  negativeRate[63] = char(0xBF);  // the rate's sign bit: -24
  EXPECT_NE(errorOf(negativeRate).find("frame rate"), std::string::npos) << errorOf(negativeRate);
}

// The camera travels in a 144-byte header; a 64-byte header has none.
TEST(EpiStream, CameraTravelsInTheHeader) {
  EpiStreamHeader h{4, 2, 3, 1, 4, 1};
  CameraSpec spec;
  spec.distance = 5.5, spec.planeWidth = 1.5, spec.planeHeight = 1.25, spec.trackLeft = -0.75;
  spec.trackRight = 0.5, spec.rowTop = 0.25, spec.rowBottom = -0.125, spec.nearDistance = 0.5;
  spec.farDistance = 9.0;
  h.camera = StreamCamera{spec, 0.375};
  std::stringstream s;
  {
    EpiStreamWriter w(s, h);
    w.putEpi(0, 0, Image(4, 3, PixelType::U8));
    w.putEpi(0, 1, Image(4, 3, PixelType::U8));
  }
  const std::string bytes = s.str();
  EXPECT_EQ(bytes.size(), 144u + 2u * (8u + 4u * 3u * 4u));
  std::stringstream in(bytes);
  EpiStreamReader r(in);
  ASSERT_TRUE(r.header().camera);
  const CameraSpec& got = r.header().camera->spec;
  EXPECT_EQ(got.distance, 5.5);
  EXPECT_EQ(got.planeHeight, 1.25);
  EXPECT_EQ(got.trackLeft, -0.75);
  EXPECT_EQ(got.rowBottom, -0.125);
  EXPECT_EQ(got.farDistance, 9.0);
  EXPECT_EQ(r.header().camera->imagePlaneZ, 0.375);
  int frames = 0;
  while (r.next()) ++frames;
  EXPECT_EQ(frames, 2);
  std::stringstream plain(streamOf({{0, 0}, {0, 1}}));
  EXPECT_FALSE(EpiStreamReader(plain).header().camera);
  // A camera value that is not a number, and a header of another size.
  std::string nan = bytes;
  for (int k = 0; k < 8; ++k) nan[64 + k] = char(0xFF);
  EXPECT_NE(errorOf(nan).find("not a finite number"), std::string::npos) << errorOf(nan);
  std::string odd = bytes;
  odd[8] = char(100);
  EXPECT_NE(errorOf(odd).find("unsupported header size 100"), std::string::npos) << errorOf(odd);
  EXPECT_NE(errorOf(bytes.substr(0, 100)).find("truncated header camera"), std::string::npos);
}

}  // namespace
}  // namespace mvr
