// mpirun -np K mvr render: the same set as one process, byte for byte,
// with 1, 2 and 3 ranks (oversubscribed on small machines); one error line
// for a bad scene; no complete-looking set when a rank dies; the EPI
// stream byte for byte.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "mvr/images/image_file.h"
#include "tests/support/asset_scene.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

bool haveMpirun() { return test::shell("command -v mpirun >/dev/null").status == 0; }

// mpirun refuses root unless told; CI runs as root.
std::string mpirun(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
         "mpirun --oversubscribe -np " + std::to_string(ranks) + " ";
}

std::map<std::string, std::string> imagesIn(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".png") continue;
    std::stringstream ss;
    ss << std::ifstream(e.path(), std::ios::binary).rdbuf();
    files[e.path().filename().string()] = ss.str();
  }
  return files;
}

nlohmann::json manifestOf(const fs::path& dir) {
  return nlohmann::json::parse(std::ifstream(dir / "manifest.json"));
}

struct SplitCase {
  const char* name;
  const char* args;
};

class MpiRender : public ::testing::TestWithParam<SplitCase> {};

TEST_P(MpiRender, OneTwoAndThreeRanksWriteTheSingleProcessSet) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed (scripts/setup installs Open MPI)";
  std::string args = std::string(GetParam().args) + " --size 64x40 --views 7";
  if (const size_t at = args.find("{assets}"); at != std::string::npos)
    args.replace(at, 8, test::writeAssetScene(test::freshDir("mpi_asset_scene")));
  const fs::path single = test::freshDir(std::string("mpi_single_") + GetParam().name);
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + args + " --out " + single.string())));
  const auto expected = imagesIn(single);
  ASSERT_GE(expected.size(), 7u);
  for (int ranks : {1, 2, 3}) {
    const fs::path dir = test::freshDir(std::string("mpi_") + std::to_string(ranks) + GetParam().name);
    const test::CliResult r =
        test::shell(mpirun(ranks) + test::mvrBinary() + " render " + args + " --out " + dir.string() + " >/dev/null");
    ASSERT_TRUE(test::succeeded(r));
    const auto got = imagesIn(dir);
    ASSERT_EQ(got.size(), expected.size()) << ranks << " ranks";
    for (const auto& [name, bytes] : expected) EXPECT_TRUE(got.at(name) == bytes) << name << ", " << ranks << " ranks";
    // Depth maps by value: an EXR header holds its write time.
    size_t depthMaps = 0;
    for (const auto& e : fs::directory_iterator(single)) {
      if (e.path().extension() != ".exr") continue;
      ++depthMaps;
      EXPECT_EQ(readDepthImage(e.path().string()).values, readDepthImage((dir / e.path().filename()).string()).values)
          << e.path().filename() << ", " << ranks << " ranks";
    }
    EXPECT_EQ(depthMaps, args.find("--depth") != std::string::npos ? expected.size() : 0u);
    const nlohmann::json m = manifestOf(dir);
    EXPECT_EQ(m["files"], manifestOf(single)["files"]);
    if (ranks > 1) {
      EXPECT_EQ(m["mpi"]["ranks"], ranks);
    }
    else EXPECT_FALSE(m.contains("mpi"));  // one rank is the single-process program
    fs::remove_all(dir);
  }
  fs::remove_all(single);
}

INSTANTIATE_TEST_SUITE_P(
    Splits, MpiRender,
    ::testing::Values(SplitCase{"mvr_views_quilt", "--backend mvr --quilt auto"},    // scanline bands, reordered
                      SplitCase{"cpu_epis", "--backend mvr --pst cpu --order epi"},  // bands, written directly
                      SplitCase{"svr_epis", "--backend svr --order epi"},            // views, reordered
                      SplitCase{"interp_rows", "--backend interp --rows 3"},  // rows; 2 ranks: a row each, then bands
                      SplitCase{"mvr_rows_views", "--backend mvr --rows 4"},  // 3 ranks: a row each, then bands
                      // Bands of sample scanlines and runs of sample views; the depth pass split alike.
                      SplitCase{"mvr_aa_depth", "--backend mvr --rows 3 --aa 2 --aa-views 2 --depth"},
                      SplitCase{"svr_depth", "--backend svr --depth"},
                      // A glTF and an OBJ with their textures (tests/support/asset_scene.h).
                      SplitCase{"assets_depth", "{assets} --backend mvr --rows 2 --depth"}),
    [](const auto& info) { return std::string(info.param.name); });

std::string contentsOf(const fs::path& file) {
  std::stringstream ss;
  ss << std::ifstream(file, std::ios::binary).rdbuf();
  return ss.str();
}

// The EPI stream: every rank writes its records at their offsets (a file)
// or rank 0 relays them in order (a pipe); the bytes are one process's.
class MpiStream : public ::testing::TestWithParam<SplitCase> {};

TEST_P(MpiStream, RanksWriteTheSingleProcessStream) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  std::string args = std::string(GetParam().args) + " --size 64x40 --views 7";
  if (const size_t at = args.find("{assets}"); at != std::string::npos)
    args.replace(at, 8, test::writeAssetScene(test::freshDir("mpi_asset_scene")));
  const fs::path dir = test::freshDir(std::string("mpi_stream_") + GetParam().name);
  fs::create_directories(dir);
  const std::string single = (dir / "single.epi").string();
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + args + " --stream " + single)));
  const std::string expected = contentsOf(single);
  ASSERT_GT(expected.size(), 144u);
  for (int ranks : {1, 2, 3}) {
    const fs::path file = dir / ("ranks" + std::to_string(ranks) + ".epi");
    const test::CliResult r =
        test::shell(mpirun(ranks) + test::mvrBinary() + " render " + args + " --stream " + file.string());
    ASSERT_TRUE(test::succeeded(r));
    EXPECT_TRUE(contentsOf(file) == expected) << ranks << " ranks";
    EXPECT_FALSE(fs::exists(file.string() + ".part"));
  }
  // To stdout through mpirun, relayed by rank 0.
  const fs::path piped = dir / "piped.epi";
  const test::CliResult r = test::shell("cd " + dir.string() + " && " + mpirun(2) + test::mvrBinary() + " render " +
                                        args + " --stream - > " + piped.string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_TRUE(contentsOf(piped) == expected);
  EXPECT_FALSE(fs::exists(dir / ".mvr_split_stream"));  // the relay's scratch file is gone
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(
    Splits, MpiStream,
    ::testing::Values(SplitCase{"mvr_bands", "--backend mvr"},          // EPIs in scanline bands, written in place
                      SplitCase{"svr_rows", "--backend svr --rows 3"}),  // 2 ranks: a row each, then views exchanged
    [](const auto& info) { return std::string(info.param.name); });

// A sequence under mpirun: the ranks share its frames, each a whole set;
// every frame, sequence.json and the video (encoded once, by rank 0, from
// the finished frames) are one process's bytes, and --resume under ranks
// renders only the frames that are missing.
TEST(MpiSequence, RanksShareTheFramesOfTheSingleProcessSequence) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string args = "render " + test::assetsDir() +
                           "/teacup_4k.ply --frames 5 --turntable 90 --quilt portrait --quilt-only --size 42x56 "
                           "--focal center --video --out ";
  const fs::path single = test::freshDir("mpi_seq_single");
  ASSERT_TRUE(test::succeeded(test::runMvr(args + single.string())));
  const std::string video = "quilt_qs8x6a0.75.mp4";
  const auto sameAsSingle = [&](const fs::path& dir, const std::string& what) {
    for (int k = 0; k < 5; ++k) {
      const std::string frame = "frame_000" + std::to_string(k);
      const auto expected = imagesIn(single / frame);
      ASSERT_EQ(expected.size(), 1u);
      EXPECT_EQ(imagesIn(dir / frame), expected) << frame << ", " << what;
    }
    EXPECT_TRUE(contentsOf(dir / video) == contentsOf(single / video)) << what;
    EXPECT_FALSE(fs::exists(dir / ".video")) << what;  // the frames handed to rank 0's encoder
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir / "sequence.json")),
              nlohmann::json::parse(std::ifstream(single / "sequence.json")))
        << what;
  };
  for (int ranks : {2, 3}) {
    const fs::path dir = test::freshDir("mpi_seq_" + std::to_string(ranks));
    const test::CliResult r = test::shell(mpirun(ranks) + test::mvrBinary() + " " + args + dir.string() + " >/dev/null");
    ASSERT_TRUE(test::succeeded(r));
    sameAsSingle(dir, std::to_string(ranks) + " ranks");
    if (ranks == 2) {
      // Frames 1 and 4 lost (rank 1's and rank 0's): --resume renders those two.
      fs::remove_all(dir / "frame_0001"), fs::remove_all(dir / "frame_0004"), fs::remove(dir / video);
      const auto kept = fs::last_write_time(dir / "frame_0002" / "manifest.json");
      const test::CliResult resumed =
          test::shell(mpirun(2) + test::mvrBinary() + " " + args + dir.string() + " --resume >/dev/null");
      ASSERT_TRUE(test::succeeded(resumed));
      EXPECT_NE(resumed.err.find("rendered 2 of 5 frames"), std::string::npos) << resumed.err;
      EXPECT_EQ(fs::last_write_time(dir / "frame_0002" / "manifest.json"), kept);
      sameAsSingle(dir, "resumed under 2 ranks");
    }
    fs::remove_all(dir);
  }
  fs::remove_all(single);
}

TEST(MpiSequence, AStreamedSequenceUnderRanksIsOneLineError) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const test::CliResult r = test::shell(mpirun(2) + test::mvrBinary() +
                                        " render --frames 3 --turntable 30 --views 4 --size 32x24 --stream /dev/null");
  EXPECT_TRUE(test::failed(r));
  EXPECT_NE(r.err.find("not split across ranks"), std::string::npos) << r.err;
}

TEST(MpiRenderErrors, ABadSceneFailsTheJobWithOneLine) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const fs::path dir = test::freshDir("mpi_bad");
  const test::CliResult r = test::shell(mpirun(2) + test::mvrBinary() + " render /no/such/scene.ply --out " +
                                        dir.string());
  EXPECT_TRUE(test::failed(r));
  size_t lines = 0;
  for (size_t at = 0; (at = r.err.find("mvr: ", at)) != std::string::npos; ++at) ++lines;
  EXPECT_EQ(lines, 1u) << r.err;
  EXPECT_NE(r.err.find("mvr: /no/such/scene.ply: no such mesh file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "manifest.json"));
}

TEST(MpiRenderErrors, AStreamFileThatCannotBeCreatedFailsWithOneLine) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const test::CliResult r =
      test::shell(mpirun(2) + test::mvrBinary() + " render --views 4 --size 32x24 --stream /no/such/dir/x.epi");
  EXPECT_TRUE(test::failed(r));
  EXPECT_NE(r.err.find("mvr: /no/such/dir/x.epi: cannot create the stream file"), std::string::npos) << r.err;
  size_t lines = 0;
  for (size_t at = 0; (at = r.err.find("mvr: ", at)) != std::string::npos; ++at) ++lines;
  EXPECT_EQ(lines, 1u) << r.err;
}

// A rank killed while the others write: the job fails and no manifest
// says the set is complete.
TEST(MpiRenderErrors, ARankThatDiesLeavesNoCompleteSet) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const fs::path dir = test::freshDir("mpi_killed");
  // Once files appear, rank 1 (found by its output folder in its command
  // line and its rank in its environment) is killed.
  const std::string killRankOne =
      "for i in $(seq 300); do sleep 0.1; [ \"$(ls " + dir.string() + " 2>/dev/null | wc -l)\" -gt 3 ] && break; done; "
      "for p in $(pgrep -f '" + dir.filename().string() + "'); do tr '\\0' '\\n' < /proc/$p/environ 2>/dev/null | "
      "grep -qx OMPI_COMM_WORLD_RANK=1 && kill -9 $p; done";
  const test::CliResult r = test::shell(mpirun(2) + test::mvrBinary() + " render --backend svr --views 3000 --size 160x120 --out " +
                                        dir.string() + " >/dev/null & " + killRankOne + "; wait $!");
  EXPECT_TRUE(test::failed(r)) << "the job finished before rank 1 was killed";
  EXPECT_FALSE(fs::exists(dir / "manifest.json"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mvr
