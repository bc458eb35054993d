// The slice table in GPU buffers: a round trip keeps every entry, and the
// rasterizers give the same EPIs from either form of the table, into
// their own images or into memory a sink lends.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <vector>

#include "epi/epi_rasterizer.h"
#include "mvr/gl/readback_ring.h"
#include "mvr/assets/scene_io.h"
#include "shading/lighting.h"
#include "slicing/extreme_vertices.h"
#include "slicing/gpu/gpu_slice_table.h"
#include "slicing/slice_table_view.h"
#include "tests/support/capture_sink.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

class GpuSliceTableTest : public test::GlTest {
 protected:
  void SetUp() override {
    test::GlTest::SetUp();
    scene = loadScene(test::assetPath("default.json"));
    camera.emplace(cameraFor(scene, 64, 48), 64, 48, 6);
    vertices = transformToExtremes(scene, shading::litVertexColors(scene), *camera, 0);
    table = SliceTable::build(vertices, camera->height());
  }
  Scene scene;
  std::optional<ShearingCamera> camera;
  ExtremeVertices vertices;
  SliceTable table;
};

TEST_F(GpuSliceTableTest, RoundTripKeepsEveryEntry) {
  ASSERT_GT(table.sliceCount(), 100u);
  const GpuSliceTable device = GpuSliceTable::upload(table);
  EXPECT_EQ(device.height(), table.height());
  EXPECT_EQ(device.sliceCount(), table.sliceCount());
  const SliceTable back = device.download();
  ASSERT_EQ(back.offsets().size(), table.offsets().size());
  ASSERT_EQ(back.slices().size(), table.slices().size());
  EXPECT_EQ(std::memcmp(back.offsets().data(), table.offsets().data(), table.offsets().size_bytes()), 0);
  EXPECT_EQ(std::memcmp(back.slices().data(), table.slices().data(), table.slices().size_bytes()), 0);
}

TEST_F(GpuSliceTableTest, EmptyTableRoundTrips) {
  const SliceTable empty = SliceTable::fromArrays({0, 0, 0}, {});
  const SliceTable back = GpuSliceTable::upload(empty).download();
  EXPECT_EQ(back.height(), 2);
  EXPECT_EQ(back.sliceCount(), 0u);
}

TEST_F(GpuSliceTableTest, ViewMakesTheOtherFormOnDemand) {
  const SliceTableView fromHost(table);
  EXPECT_TRUE(fromHost.onHost());
  EXPECT_EQ(&fromHost.host(), &table);
  EXPECT_EQ(fromHost.device().sliceCount(), table.sliceCount());
  const GpuSliceTable device = GpuSliceTable::upload(table);
  const SliceTableView fromDevice(device);
  EXPECT_TRUE(fromDevice.onDevice());
  EXPECT_EQ(&fromDevice.device(), &device);
  EXPECT_EQ(fromDevice.host().sliceCount(), table.sliceCount());
  EXPECT_EQ(&fromDevice.host(), &fromDevice.host()) << "downloaded once and kept";
}

// Every rasterizer fills the same EPIs from a GPU-resident table as from the
// host table it came from: bit for bit, since the entries are the same.
TEST_F(GpuSliceTableTest, RasterizersGiveTheSameEpisFromEitherForm) {
  const GpuSliceTable device = GpuSliceTable::upload(table);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact, PstMode::Strip}) {
    auto rasterizer = makeRasterizer(mode, PixelType::U8);
    test::CaptureSink fromHost, fromDevice;
    RenderStats stats;
    rasterizer->rasterize(vertices, table, *camera, 0, fromHost, stats);
    rasterizer->rasterize(vertices, device, *camera, 0, fromDevice, stats);
    ASSERT_EQ(fromHost.epis.size(), size_t(camera->height())) << pstModeName(mode);
    for (const auto& [key, epi] : fromHost.epis)
      ASSERT_EQ(epi.bytes, fromDevice.epis.at(key).bytes) << pstModeName(mode) << " scanline " << key.second;
  }
}

// Lends memory (FrameSink::epiMemory) for every other scanline, filled
// with a pattern no rasterizer writes, and keeps what is handed on.
class LendingSink final : public FrameSink {
 public:
  std::map<int, std::vector<uint8_t>> lent;
  std::map<int, Image> handed;
  void putEpi(int, int scanline, const Image& epi) override { handed[scanline] = epi; }
  uint8_t* epiMemory(int, int scanline, int width, int views, PixelType type) override {
    if (scanline % 2) return nullptr;
    std::vector<uint8_t>& m = lent[scanline];
    m.assign(size_t(width) * views * 4 * Image::channelBytes(type), 0xA5);
    return m.data();
  }
};

// Where a sink lends memory, every rasterizer fills it with the bytes it
// would have handed on, and hands on only the EPIs it filled itself; with
// the readback ring's reads staged too (a GPU's path: they land later).
TEST_F(GpuSliceTableTest, RasterizersFillTheMemoryASinkLends) {
  const GpuSliceTable device = GpuSliceTable::upload(table);
  auto check = [&](PstMode mode, PstBuilder builder, const std::string& label) {
    auto rasterizer = makeRasterizer(mode, PixelType::U8, {}, builder);
    test::CaptureSink own;
    LendingSink lending;
    RenderStats stats;
    rasterizer->rasterize(vertices, table, *camera, 0, own, stats);
    if (rasterizer->readsDeviceTable()) rasterizer->rasterize(vertices, device, *camera, 0, lending, stats);
    else rasterizer->rasterize(vertices, table, *camera, 0, lending, stats);
    ASSERT_EQ(lending.lent.size() + lending.handed.size(), size_t(camera->height())) << label;
    for (const auto& [key, epi] : own.epis) {
      const int j = key.second;
      if (j % 2) {
        ASSERT_TRUE(lending.handed.count(j)) << label << " scanline " << j;
        EXPECT_EQ(lending.handed.at(j).bytes, epi.bytes) << label << " scanline " << j;
      } else {
        EXPECT_FALSE(lending.handed.count(j)) << label << " handed on lent scanline " << j;
        EXPECT_EQ(ImageBytes(lending.lent.at(j).begin(), lending.lent.at(j).end()), epi.bytes) << label << " scanline " << j;
      }
    }
  };
  for (ReadbackStaging staging : {ReadbackStaging::Never, ReadbackStaging::Always}) {
    setReadbackStaging(staging);
    const std::string staged = staging == ReadbackStaging::Always ? ", staged" : "";
    check(PstMode::Cpu, PstBuilder::Auto, "cpu");
    check(PstMode::Spans, PstBuilder::Auto, "spans" + staged);
    for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact})
      for (PstBuilder builder : {PstBuilder::Cpu, PstBuilder::Gpu})
        check(mode, builder, pstModeName(mode) + std::string(builder == PstBuilder::Gpu ? " gpu" : " cpu") + staged);
  }
  setReadbackStaging(ReadbackStaging::Auto);
}

}  // namespace
}  // namespace mvr
