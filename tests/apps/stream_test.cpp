// `mvr stream` and `mvr-consume` as two processes: the views the consumer
// assembles equal the image set `mvr render` writes.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

const std::string kArgs = " --views 6 --size 56x40 --pst cpu";

void expectSameSet(const std::filesystem::path& a, const std::filesystem::path& b) {
  auto diffs = compareSets(a.string(), b.string());
  ASSERT_EQ(diffs.size(), 6u);
  for (const auto& d : diffs) EXPECT_EQ(d.identicalFraction, 1.0) << d.name;
}

// `mvr stream ARGS --to -` piped into mvr-consume writing `got`.
test::CliResult streamToConsumer(const std::string& args, const std::filesystem::path& got) {
  return test::shell(test::mvrBinary() + " stream" + args + " --to - | " + test::consumeBinary() + " --from - --out " +
                     got.string());
}

TEST(Stream, PipeProducerToConsumer) {
  auto ref = test::freshDir("stream_ref"), got = test::freshDir("stream_pipe");
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kArgs + " --out " + ref.string())));
  auto r = streamToConsumer(kArgs + " --queue 2", got);
  ASSERT_TRUE(test::succeeded(r));
  expectSameSet(ref, got);
}

// The consumer's manifest carries the producer's camera: the same per-view
// cameras `mvr render` records for the same command line.
TEST(Stream, ConsumerManifestHasTheRenderCameras) {
  auto ref = test::freshDir("stream_cam_ref"), got = test::freshDir("stream_cam_got");
  const std::string args = kArgs + " --cone 30 --focal center";
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + args + " --out " + ref.string())));
  auto r = streamToConsumer(args, got);
  ASSERT_TRUE(test::succeeded(r));
  const auto a = nlohmann::json::parse(std::ifstream(ref / "manifest.json"));
  const auto b = nlohmann::json::parse(std::ifstream(got / "manifest.json"));
  ASSERT_TRUE(b.contains("cameras")) << b.dump();
  EXPECT_EQ(a["cameras"], b["cameras"]);
  EXPECT_EQ(a["camera"], b["camera"]);
  EXPECT_FALSE(b["camera"].contains("rows_track"));  // one row: its y, not a track
  EXPECT_TRUE(b["camera"].contains("row_y"));
}

// A sequence streamed (issue 47): the consumer writes each frame's set in
// frame_0000/, ... equal to those `mvr render --frames` writes, byte for
// byte, and its manifest says the frame's time. Flags for frame folders
// are refused with a stream.
TEST(Stream, SequenceFramesEqualTheRenderedSequence) {
  auto ref = test::freshDir("stream_seq_ref"), got = test::freshDir("stream_seq_got");
  const std::string args = kArgs + " --frames 3 --fps 4 --turntable 60";
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + args + " --out " + ref.string())));
  auto r = streamToConsumer(args, got);
  ASSERT_TRUE(test::succeeded(r));
  for (const char* frame : {"frame_0000", "frame_0001", "frame_0002"}) expectSameSet(ref / frame, got / frame);
  EXPECT_FALSE(std::filesystem::exists(got / "frame_0003"));
  const auto m = nlohmann::json::parse(std::ifstream(got / "frame_0002" / "manifest.json"));
  EXPECT_DOUBLE_EQ(m["frame"]["time_s"].get<double>(), 0.5) << m.dump();
  // Frames differ: the turn shows.
  EXPECT_LT(compareImages(readImage((got / "frame_0000" / "view_0000.png").string()),
                          readImage((got / "frame_0002" / "view_0000.png").string()))
                .identicalFraction,
            0.9);
  const auto resume = test::runMvr("render" + args + " --resume --stream " + (got / "x.epi").string());
  EXPECT_TRUE(test::exitedWith(resume, 1));
  EXPECT_NE(resume.err.find("--resume: keeps complete frame folders: not with a stream"), std::string::npos) << resume.err;
  EXPECT_FALSE(std::filesystem::exists(got / "x.epi"));
}

TEST(Stream, UnixSocketProducerToListeningConsumer) {
  auto ref = test::freshDir("sock_ref"), got = test::freshDir("sock_got");
  const std::string sock = (std::filesystem::temp_directory_path() /
                            ("mvr_test_" + std::to_string(getpid()) + ".sock")).string();
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kArgs + " --out " + ref.string())));
  // The consumer listens; the producer retries until the socket exists.
  auto r = test::shell(test::consumeBinary() + " --from unix:" + sock + " --out " + got.string() +
                       " & for i in $(seq 50); do [ -S " + sock + " ] && break; sleep 0.1; done; " +
                       test::mvrBinary() + " stream" + kArgs + " --to unix:" + sock + " && wait");
  ASSERT_TRUE(test::succeeded(r));
  expectSameSet(ref, got);
}

// A named pipe (or a device such as /dev/null) is written in place: a
// temporary name renamed over it would replace it with a regular file.
TEST(Stream, NamedPipeIsWrittenInPlace) {
  auto ref = test::freshDir("fifo_ref"), got = test::freshDir("fifo_got"), dir = test::freshDir("fifo");
  std::filesystem::create_directories(dir);
  const std::string fifo = (dir / "epis").string();
  ASSERT_TRUE(test::succeeded(test::shell("mkfifo " + fifo)));
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kArgs + " --out " + ref.string())));
  auto r = test::shell("timeout 60 " + test::consumeBinary() + " --from " + fifo + " --out " + got.string() + " & " +
                       test::mvrBinary() + " stream" + kArgs + " --to " + fifo + " && wait $!");
  ASSERT_TRUE(test::succeeded(r));
  expectSameSet(ref, got);
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_FALSE(std::filesystem::exists(fifo + ".part"));
}

TEST(Stream, FileStreamAndTruncationIsReported) {
  auto file = test::freshDir("stream_file");
  std::filesystem::create_directories(file);
  const std::string path = (file / "set.epis").string();
  ASSERT_TRUE(test::succeeded(test::runMvr("stream" + kArgs + " --to " + path)));
  EXPECT_FALSE(std::filesystem::exists(path + ".part"));
  const auto size = std::filesystem::file_size(path);
  EXPECT_EQ(size, 144u + 40u * (8u + 56u * 6u * 4u));  // the header with the camera
  std::filesystem::resize_file(path, size - 100);
  auto r = test::shell(test::consumeBinary() + " --from " + path + " --out " + (file / "out").string());
  EXPECT_TRUE(test::failed(r));
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(file / "out" / "manifest.json"));
}

TEST(Stream, ConsumerGoneIsAnErrorNotAHang) {
  // pipefail: the pipeline's status is the producer's, not head's.
  auto r = test::shell("bash -o pipefail -c '" + test::mvrBinary() +
                       " stream --views 64 --size 256x200 --to - | head -c 100 >/dev/null'");
  EXPECT_TRUE(test::exitedWith(r, 1)) << r.err;
  EXPECT_EQ(r.err, "mvr: -: cannot write stream: Broken pipe\n");
}

}  // namespace
}  // namespace mvr
