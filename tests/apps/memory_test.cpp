// A memory budget smaller than a row of frames sends the reordering
// through a scratch file; the files written must be byte-identical to the
// in-memory path's (issue 15), and nothing of the scratch file may remain.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "tests/support/cli.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Same file names, same bytes; the manifests differ in timings only.
void expectSameFiles(const fs::path& a, const fs::path& b) {
  size_t images = 0;
  for (const auto& entry : fs::directory_iterator(a)) {
    const fs::path name = entry.path().filename();
    if (name == "manifest.json") continue;
    ASSERT_TRUE(fs::exists(b / name)) << name;
    EXPECT_TRUE(bytesOf(entry.path()) == bytesOf(b / name)) << name << " differs";
    ++images;
  }
  EXPECT_GT(images, 0u);
  EXPECT_EQ(std::distance(fs::directory_iterator(a), {}), std::distance(fs::directory_iterator(b), {}))
      << "extra files in " << b;
}

nlohmann::json reorderOf(const fs::path& set) {
  return nlohmann::json::parse(std::ifstream(set / "manifest.json")).at("reorder");
}

// 48x36 RGBA8 views are 6912 bytes; with one thread the encoders hold 2
// frames and their files (27,648 bytes), so 48K leaves 21,504 bytes: 3 views.
// Float views (16-bit files) are 27,648 bytes: 190K leaves 3 of them.
const std::string kJob = " --size 48x36 --views 12 --threads 1";

TEST(MemoryBudget, MvrViewsThroughScratchAreByteIdentical) {
  const fs::path memory = test::freshDir("budget_mem"), scratch = test::freshDir("budget_scratch");
  // PNG views within the budget are encoded from the EPIs' rows
  // (mvr/frames/png_views.h), 8-bit ones from byte EPIs, 16-bit ones from float
  // EPIs: over the budget both go through the scratch file, to the same
  // bytes.
  for (const std::string bits : {"8", "16"})
    for (const std::string rows : {"1", "2"}) {  // two rows reuse the scratch file
      fs::remove_all(memory), fs::remove_all(scratch);
      const std::string job = "render --backend mvr --pst cpu --bits " + bits + " --rows " + rows + kJob;
      ASSERT_TRUE(test::succeeded(test::runMvr(job + " --out " + memory.string())));
      const auto r = test::runMvr(job + " --memory " + (bits == "8" ? "48K" : "190K") + " --out " + scratch.string());
      ASSERT_TRUE(test::succeeded(r));
      expectSameFiles(memory, scratch);
      EXPECT_EQ(reorderOf(scratch)["scratch_file"], true);
      EXPECT_EQ(reorderOf(scratch)["frames_per_pass"], 3);
      EXPECT_EQ(reorderOf(memory)["scratch_file"], false);
      EXPECT_EQ(reorderOf(memory)["method"], "EPI rows into the views' PNG encoders");
    }
}

TEST(MemoryBudget, SvrEpisThroughScratchAreByteIdentical) {
  const fs::path memory = test::freshDir("budget_epi_mem"), scratch = test::freshDir("budget_epi_scratch");
  // A float volume, written as 16-bit PNG (EXR files carry their time of writing).
  const std::string job = "render --backend svr --order epi --bits 16" + kJob;
  ASSERT_TRUE(test::succeeded(test::runMvr(job + " --out " + memory.string())));
  const auto r = test::runMvr(job + " --memory 100K --out " + scratch.string());
  ASSERT_TRUE(test::succeeded(r));
  expectSameFiles(memory, scratch);
  EXPECT_EQ(reorderOf(scratch)["scratch_file"], true);
}

TEST(MemoryBudget, StreamAndConsumerThroughScratchAreByteIdentical) {
  const fs::path dir = test::freshDir("budget_stream");
  fs::create_directories(dir);
  const std::string job = "stream --backend svr" + kJob;
  ASSERT_TRUE(test::succeeded(test::runMvr(job + " --to " + (dir / "memory.epis").string())));
  auto r = test::runMvr(job + " --memory 48K --scratch " + dir.string() + " --to " +
                        (dir / "scratch.epis").string());
  ASSERT_TRUE(test::succeeded(r));
  // 48x12 EPIs; the queue holds 8 and their copies (36,864 bytes): 5 per pass.
  EXPECT_NE(r.err.find("reordered through a scratch file, 5 frames per pass"), std::string::npos) << r.err;
  EXPECT_TRUE(bytesOf(dir / "memory.epis") == bytesOf(dir / "scratch.epis"));
  // The consumer reassembles views under a budget too.
  for (const std::string budget : {"", " --memory 48K"}) {
    const fs::path out = dir / (budget.empty() ? "views_memory" : "views_scratch");
    r = test::shell(test::consumeBinary() + " --threads 1 --from " + (dir / "memory.epis").string() +
                    budget + " --out " + out.string());
    ASSERT_TRUE(test::succeeded(r));
    EXPECT_EQ(r.err.find("through a scratch file, 3 frames per pass") != std::string::npos, !budget.empty())
        << r.err;
    // Within the budget the rows go straight into the views' encoders.
    EXPECT_EQ(reorderOf(out)["method"],
              budget.empty() ? "EPI rows into the views' PNG encoders" : "scratch file");
  }
  expectSameFiles(dir / "views_memory", dir / "views_scratch");
}

}  // namespace
}  // namespace mvr
