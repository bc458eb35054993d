// The extreme-view transform on the GPU against transformToExtremes, its
// CPU oracle: the same records (bit for bit almost everywhere; x within
// 1e-4 px, the rest within 1e-6 relative), the same y and so the same slice
// table, on every row of a full-parallax camera; and cameras whose near or
// far plane cuts the scene are left to the CPU, which clips.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "mvr/backends/mvr/mvr_renderer.h"
#include "mvr/assets/scene_io.h"
#include "shading/lighting.h"
#include "slicing/extreme_vertices.h"
#include "slicing/gpu/gpu_slicer.h"
#include "slicing/gpu/gpu_transform.h"
#include "slicing/slice_table.h"
#include "tests/support/gl_fixture.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

class GpuTransformTest : public test::GlTest {};

TEST_F(GpuTransformTest, RecordsAndTablesMatchTheCpuTransform) {
  for (const char* name : {"default.json", "textured.json", "mirror.json"}) {
    const Scene scene = loadScene(test::assetPath(name));
    CameraSpec spec = *scene.camera;
    spec.rowTop = 0.4, spec.rowBottom = -0.4;
    const ShearingCamera cam(spec, 64, 48, 6, 3);
    ASSERT_TRUE(GpuExtremeTransform::needsNoClipping(scene.bounds(), cam)) << name;
    const shading::ShadingPlan plan = shading::planShading(scene);
    const shading::VertexColors colors = shading::litVertexColors(scene);
    const std::vector<float> extras = shading::vertexExtras(scene, plan);
    GpuExtremeTransform gpu(scene, colors, extras, plan.extraCount);
    GpuSlicer slicer;
    for (int row = 0; row < cam.rows(); ++row) {
      const ExtremeVertices cpu = transformToExtremes(scene, colors, cam, row, extras, plan.extraCount);
      const GpuVertices expected = GpuVertices::upload(cpu);
      const GpuVertices& got = gpu.transform(cam, row);
      ASSERT_EQ(got.vertexCount, expected.vertexCount) << name;
      ASSERT_EQ(got.recordStride, expected.recordStride) << name;
      const size_t floats = got.vertexCount * size_t(got.recordStride);
      const auto a = test::download<float>(expected.records.id(), floats), b = test::download<float>(got.records.id(), floats);
      size_t identical = 0, far = 0;
      for (size_t i = 0; i < floats; ++i) {
        identical += a[i] == b[i];
        const int field = int(i % got.recordStride);
        const float tolerance = field < 2 ? 1e-4f : 1e-6f * std::max(1.0f, std::abs(a[i]));
        far += !(std::abs(a[i] - b[i]) <= tolerance);
      }
      EXPECT_EQ(far, 0u) << name << " row " << row;
      EXPECT_GE(double(identical) / double(floats), 0.99) << name << " row " << row;
      const auto y = test::download<float>(gpu.yBuffer(), got.vertexCount);
      for (size_t i = 0; i < y.size(); ++i) ASSERT_NEAR(y[i], cpu.y[i], 1e-4f) << name << " vertex " << i;
      const SliceTable table =
          slicer.build(gpu.yBuffer(), got.triangles.id(), uint32_t(got.triangleCount), cam.height()).download();
      const SliceTable oracle = SliceTable::build(cpu, cam.height());
      ASSERT_EQ(table.sliceCount(), oracle.sliceCount()) << name << " row " << row;
      EXPECT_TRUE(std::equal(table.offsets().begin(), table.offsets().end(), oracle.offsets().begin()));
    }
  }
}

TEST_F(GpuTransformTest, CamerasThatClipTheSceneTransformOnTheCpu) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  CameraSpec spec = *scene.camera;
  const Bounds b = scene.bounds();
  const ShearingCamera framed(spec, 48, 36, 4);
  EXPECT_TRUE(GpuExtremeTransform::needsNoClipping(b, framed));
  // The near plane through the middle of the scene.
  spec.nearDistance = spec.distance - 0.5 * (b.min.z + b.max.z);
  const ShearingCamera cut(spec, 48, 36, 4);
  EXPECT_FALSE(GpuExtremeTransform::needsNoClipping(b, cut));
  auto gpu = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8, TextureMode::Vector, PstBuilder::Gpu);
  auto cpu = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8, TextureMode::Vector, PstBuilder::Cpu);
  for (const ShearingCamera* cam : {&framed, &cut}) {
    RenderStats gpuStats, cpuStats;
    const auto g = test::renderViews(*gpu, *cam, gpuStats);
    const auto c = test::renderViews(*cpu, *cam, cpuStats);
    EXPECT_EQ(gpuStats.notes["transform"], cam == &framed ? "gpu" : "cpu");
    EXPECT_EQ(cpuStats.notes["transform"], "cpu");
    EXPECT_EQ(gpuStats.counters["slices"], cpuStats.counters["slices"]);
    const auto d = test::compareViews(c, g);
    EXPECT_GE(d.minIdentical, 0.999);
    EXPECT_GE(d.minPsnr, 45.0);
  }
}

}  // namespace
}  // namespace mvr
