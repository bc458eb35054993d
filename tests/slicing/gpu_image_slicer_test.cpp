// The image-based slicing on the GPU against its CPU oracle,
// sliceSourceLayers: the same table (offsets equal), and per slot the same
// endpoints (within 1e-4 px, depth and 1/w within 1e-6 relative), vector
// (length, parameter range) and texels, over layers rendered from the
// default scene and over hand-made layers for the edge cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mvr/assets/scene_io.h"
#include "mvr/views/outline_triangles.h"
#include "mvr/views/source_layers.h"
#include "slicing/gpu/gpu_image_slicer.h"
#include "slicing/gpu/gpu_source_visibility.h"
#include "slicing/image_slices.h"
#include "slicing/source_visibility.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

// Slices the same layers both ways and compares them slot by slot.
// order: the store's layers in the host list's order (empty: the same).
void expectSameSlices(const std::vector<SourceLayer>& host, const DeviceLayers& device,
                      const ShearingCamera& cam, const ImageSliceOptions& options, const std::string& label,
                      const std::vector<int>& order = {}) {
  const ImageSlices cpu = sliceSourceLayers(host, cam, 0, options);
  GpuImageSlicer slicer;
  const GpuImageSlices gpu = slicer.build(device, cam, options, {}, order);
  const SliceTable table = gpu.table.download();
  ASSERT_EQ(table.sliceCount(), cpu.table.sliceCount()) << label;
  ASSERT_TRUE(std::equal(table.offsets().begin(), table.offsets().end(), cpu.table.offsets().begin())) << label;
  EXPECT_EQ(gpu.pixels, cpu.pixels) << label;
  const size_t n = table.sliceCount();
  const auto records = test::download<float>(gpu.vertices.records.id(), 2 * n * GpuVertices::kRecordHead);
  const auto vectors = test::download<glm::uvec4>(gpu.vertices.vectors.id(), n);
  const auto texels = test::download<glm::vec4>(gpu.vertices.texelBuffer, gpu.vertices.texelCount);
  int worst = 0;
  for (size_t s = 0; s < n && worst < 5; ++s) {
    const Slice& slice = cpu.table.slices()[s];
    auto [e0, e1] = sliceEnds(cpu.vertices, slice);
    for (int end = 0; end < 2; ++end) {
      const SliceEnd& e = end ? e1 : e0;
      const float* r = records.data() + (2 * s + end) * GpuVertices::kRecordHead;
      const bool close = std::abs(r[0] - e.x0) <= 1e-4f && std::abs(r[1] - e.dx) <= 1e-4f &&
                         std::abs(r[2] - e.depth) <= 1e-6f * e.depth && std::abs(r[3] - e.invW) <= 1e-6f * e.invW;
      EXPECT_TRUE(close) << label << " slot " << s << " end " << end << ": " << r[0] << " " << r[1] << " "
                         << r[2] << " " << r[3] << " vs " << e.x0 << " " << e.dx << " " << e.depth << " " << e.invW;
      worst += !close;
    }
    const SliceVector& v = cpu.vertices.vectors[slice.triangle];
    const glm::uvec4 g = vectors[s];
    ASSERT_EQ(int(g.y), v.length) << label << " slot " << s;
    EXPECT_EQ(std::bit_cast<float>(g.z), v.u0) << label;
    EXPECT_EQ(std::bit_cast<float>(g.w), v.u1) << label;
    for (int t = 0; t < 2 * v.length - 1; ++t)
      ASSERT_EQ(texels.at(g.x + t), cpu.vertices.vectorTexels.texels().at(v.base + t)) << label << " slot " << s;
  }
}

// The same layers from two source eyes, read back (host) and kept in a
// store (device).
struct BothLayers {
  BothLayers(SourceLayerRenderer& sources, const ShearingCamera& cam, std::initializer_list<double> eyes,
             int maxLayers) {
    const double track = cam.spec().trackRight - cam.spec().trackLeft;
    device.reset(cam.width(), cam.height(), 8);
    RenderStats stats;
    for (double x : eyes) {
      for (SourceLayer& l : sources.render(cam, {x, 0.0}, maxLayers, track, stats)) host.push_back(std::move(l));
      sources.render(cam, {x, 0.0}, maxLayers, track, stats, device);
    }
  }
  std::vector<SourceLayer> host;
  DeviceLayers device;
};

class GpuImageSlicerTest : public test::GlTest {};

// With and without the nearest layers' finer outlines (4 samples a pixel:
// the store keeps the read-back path's outlines, and silhouette ends move
// onto them alike).
TEST_F(GpuImageSlicerTest, RenderedLayersSliceAsOnTheCpu) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 88, 60, 9);  // 88: not a power of two
  for (int samples : {1, 4}) {
    auto sources = makeSourceLayerRenderer(scene, false, samples);
    BothLayers both(*sources, cam, {cam.viewX(0), cam.viewX(8)}, 4);
    const std::vector<SourceLayer>& host = both.host;
    const DeviceLayers& device = both.device;
    ASSERT_EQ(device.count(), int(host.size()));
    ASSERT_GE(device.count(), 4);
    const std::string label = std::to_string(samples) + " samples a pixel, ";
    const auto outlines = test::download<PixelOutline>(device.outlineBuffer(), device.pixelsPerLayer() * host.size());
    int inside = 0;  // outline ends strictly within their pixels, where read
    for (size_t k = 0; k < host.size(); ++k) {
      const bool nearest = host[k].layer == 0;
      ASSERT_EQ(device.outlined(int(k)), samples > 1 && nearest) << label << "layer " << k;
      ASSERT_EQ(host[k].outline.size(), samples > 1 && nearest ? device.pixelsPerLayer() : 0u) << label;
      if (host[k].outline.empty()) continue;
      // The read-back outline draws only the triangles that reach the
      // pixels a slicer reads, and leaves the others empty; the store draws
      // them all. Where read, the two agree bit for bit.
      const std::vector<uint8_t> read = outlinePixels(host[k].depth, cam.width(), cam.height());
      int reads = 0;
      for (size_t p = 0; p < host[k].outline.size(); ++p) {
        const PixelOutline& h = host[k].outline[p], &d = outlines[k * device.pixelsPerLayer() + p];
        if (!read[p]) {
          ASSERT_LT(h.right, 0.0f) << label << "layer " << k << " pixel " << p;
          continue;
        }
        ASSERT_TRUE(h.left == d.left && h.leftDepth == d.leftDepth && h.right == d.right && h.rightDepth == d.rightDepth)
            << label << "layer " << k << " pixel " << p;
        inside += h.left > 0.0f || (h.right > 0.0f && h.right < 1.0f);
        ++reads;
      }
      EXPECT_GT(reads, 50) << label << "layer " << k;
    }
    if (samples > 1) {
      EXPECT_GT(inside, 50) << label;
    }
    for (float coalesce : {0.0f, 0.5f, 2.0f})
      for (float overlap : {0.0f, 0.25f})
        expectSameSlices(host, device, cam, {overlap, coalesce},
                         label + "coalesce " + std::to_string(coalesce) + " overlap " + std::to_string(overlap));
    // The second source first: a scanline's slices follow the order given
    // (interp's pieces list their near source first, wherever the store
    // holds it).
    std::vector<SourceLayer> swapped;
    std::vector<int> order;
    for (int pass = 0; pass < 2; ++pass)
      for (size_t k = 0; k < host.size(); ++k)
        if ((host[k].eye.x == cam.viewX(0)) == (pass == 1)) swapped.push_back(host[k]), order.push_back(int(k));
    expectSameSlices(swapped, device, cam, {0.25f, 0.0f}, label + "second source first", order);
  }
}

// The store's peel issues every layer at once and cuts the empty tail from
// the sample counts afterwards: it keeps the layers the read-back peel
// keeps, whether the limit stops the peel or the scene's depth does.
TEST_F(GpuImageSlicerTest, TheStoreKeepsTheLayersTheReadBackPeelKeeps) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 64, 48, 5);
  auto sources = makeSourceLayerRenderer(scene);
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  RenderStats stats;
  bool cutByDepth = false;
  for (int maxLayers : {1, 2, 16}) {
    const std::vector<SourceLayer> host = sources->render(cam, {cam.viewX(0), 0.0}, maxLayers, track, stats);
    DeviceLayers device;
    device.reset(cam.width(), cam.height(), 2 * maxLayers);
    const int added = sources->render(cam, {cam.viewX(0), 0.0}, maxLayers, track, stats, device);
    sources->render(cam, {cam.viewX(4), 0.0}, maxLayers, track, stats, device);  // appended after the cut
    ASSERT_EQ(added, int(host.size())) << maxLayers << " layers at most";
    cutByDepth |= added < maxLayers;
    for (int k = 0; k < added; ++k) {
      const Image color = device.readColor(k);
      EXPECT_EQ(color.bytes, host[size_t(k)].color.bytes) << "layer " << k << " of " << maxLayers;
    }
    EXPECT_GE(device.count(), added + 1);
    EXPECT_EQ(device.eye(added).x, cam.viewX(4));
  }
  EXPECT_TRUE(cutByDepth) << "the scene never ran out of layers";
}

// Hand-made layers: textures uploaded, then appended as a renderer would.
class HandLayers {
 public:
  HandLayers(int w, int h) : w_(w), h_(h) { store.reset(w, h, 8); }
  void add(const SourceLayer& layer) {
    gl::Texture color(GL_TEXTURE_2D), depth(GL_TEXTURE_2D);
    gl::TextureStorage2D(color.id(), 1, GL_RGBA32F, w_, h_);
    gl::TextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, w_, h_);
    gl::TextureSubImage2D(color.id(), 0, 0, 0, w_, h_, GL_RGBA, GL_FLOAT, layer.color.row(0));
    gl::TextureSubImage2D(depth.id(), 0, 0, 0, w_, h_, GL_DEPTH_COMPONENT, GL_FLOAT, layer.depth.data());
    gl::checkError("hand layer upload");
    store.append(layer.eye, color.id(), depth.id());
    gl::checkError("hand layer append");
    host.push_back(layer);
  }
  DeviceLayers store;
  std::vector<SourceLayer> host;

 private:
  int w_, h_;
};

SourceLayer handLayer(const ShearingCamera& cam, double eyeX, uint32_t seed, float emptyFraction) {
  SourceLayer l;
  l.eye = {eyeX, 0.0};
  l.color = Image(cam.width(), cam.height(), PixelType::F32);
  l.depth.assign(size_t(cam.width()) * cam.height(), 0.0f);
  for (int j = 0; j < cam.height(); ++j)
    for (int x = 0; x < cam.width(); ++x) {
      seed = seed * 1664525u + 1013904223u;
      const float r = float(seed >> 8) / float(1 << 24);
      if (r < emptyFraction) continue;
      // Gently sloped bands of depth, so that some runs coalesce.
      const double Z = 0.3 * std::sin(0.2 * x) + 0.05 * ((x / 13 + j) % 3);
      l.depth[size_t(j) * cam.width() + x] = float(cam.project({0.0, 0.0, Z}, 0).z);
      float* px = reinterpret_cast<float*>(l.color.row(j)) + 4 * x;
      px[0] = r, px[1] = 1.0f - r, px[2] = 0.5f, px[3] = 1.0f;
    }
  return l;
}

TEST_F(GpuImageSlicerTest, HandMadeLayersAndEdgeCases) {
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -1, spec.trackRight = 1;
  const ShearingCamera cam(spec, 37, 5, 4);  // an odd width: partial blocks at the right edge
  HandLayers layers(cam.width(), cam.height());
  layers.add(handLayer(cam, -1.0, 1, 0.1f));
  layers.add(handLayer(cam, 1.0, 2, 0.4f));
  layers.add(handLayer(cam, 0.3, 3, 1.0f));  // empty
  for (float coalesce : {0.0f, 0.3f, 3.0f, 1000.0f})
    expectSameSlices(layers.host, layers.store, cam, {0.25f, coalesce}, "coalesce " + std::to_string(coalesce));

  // One view: a track with no width coalesces every whole covered block,
  // never across an empty pixel.
  const ShearingCamera one(spec, 37, 5, 1);
  HandLayers single(one.width(), one.height());
  single.add(handLayer(one, 0.0, 4, 0.2f));
  expectSameSlices(single.host, single.store, one, {0.25f, 1.0f}, "one view");

  // No layers at all: an empty table.
  DeviceLayers none;
  none.reset(cam.width(), cam.height(), 2);
  GpuImageSlicer slicer;
  const GpuImageSlices empty = slicer.build(none, cam, {});
  EXPECT_EQ(empty.table.sliceCount(), 0u);
  EXPECT_EQ(empty.table.offsets().size(), size_t(cam.height()) + 1);
}

// Visibility on the store (GpuVisibility) against hideInvisible, its host
// oracle, on copies of the same layers: in every layer behind a nearest
// the same pixels dropped (the depths bit for bit) and the same counts
// (up to test::expectSameDecisions' allowance off llvmpipe); the nearest layers
// untouched. Returns the pixels dropped.
long expectSameVisibility(std::vector<SourceLayer> host, DeviceLayers& device, const ShearingCamera& cam,
                          float overlap, const std::string& label) {
  GpuVisibility visibility;
  const std::vector<LayerVisibility> counts = visibility.hide(device, cam, overlap);
  const size_t pixels = device.pixelsPerLayer();
  const auto depths = test::download<float>(device.depthBuffer(), pixels * host.size());
  std::vector<glm::dvec2> eyes;
  for (const SourceLayer& l : host) eyes.push_back(l.eye);
  const std::vector<int> front = nearestLayerOf(eyes);
  EXPECT_EQ(counts.size(), host.size()) << label;
  long hidden = 0;
  for (size_t k = 0; k < host.size() && k < counts.size(); ++k) {
    const long covered = long(std::count_if(host[k].depth.begin(), host[k].depth.end(), [](float d) { return d > 0.0f; }));
    const long kept = front[k] == int(k) ? 0 : hideInvisible(host[size_t(front[k])], host[k], cam, overlap);
    const std::string layer = label + " layer " + std::to_string(k);
    EXPECT_EQ(counts[k].covered, front[k] == int(k) ? 0 : covered) << layer;
    test::expectSameDecisions(counts[k].kept, kept, covered, layer + ", pixels kept");
    if (front[k] != int(k)) hidden += covered - kept;
    long differ = 0;
    for (size_t i = 0; i < pixels; ++i) differ += host[k].depth[i] != depths[k * pixels + i];
    test::expectSameDecisions(differ, 0, covered, layer + ", pixels whose depth differs");
  }
  return hidden;
}

// Rendered layers of the cup (deep: its inside behind the rim) from the
// middle of the track, where the front hides most, and an end; and
// hand-made ones whose random holes and depth steps hide some back pixels
// and open others.
TEST_F(GpuImageSlicerTest, VisibilityDropsWhatTheHostDrops) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 120, 90, 9);
  auto sources = makeSourceLayerRenderer(scene);
  for (float overlap : {0.0f, 0.1f, 0.25f}) {
    BothLayers both(*sources, cam, {cam.viewX(4), cam.viewX(0)}, 4);
    const std::vector<SourceLayer>& host = both.host;
    DeviceLayers& device = both.device;
    ASSERT_EQ(device.count(), int(host.size()));
    ASSERT_GT(device.count(), 2);
    const long hidden = expectSameVisibility(host, device, cam, overlap, "rendered, overlap " + std::to_string(overlap));
    // With no overlap every depth step is a crack that could open.
    if (overlap > 0.0f) {
      EXPECT_GT(hidden, 100) << overlap;
    }
  }
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -1, spec.trackRight = 1;
  const ShearingCamera hand(spec, 37, 5, 4);
  HandLayers layers(hand.width(), hand.height());
  // Walls at one depth with random holes, and random pixels behind them.
  auto flat = [&](SourceLayer l, double Z) {
    for (float& d : l.depth)
      if (d > 0.0f) d = float(hand.project({0.0, 0.0, Z}, 0).z);
    return l;
  };
  layers.add(flat(handLayer(hand, -1.0, 1, 0.02f), 0.2));
  layers.add(flat(handLayer(hand, -1.0, 5, 0.3f), -0.2));
  layers.add(handLayer(hand, 1.0, 2, 0.1f));  // sloped and stepped: cracks
  layers.add(handLayer(hand, 1.0, 6, 0.0f));
  // A whole wall: every back pixel but those within reach of the edges
  // hidden.
  layers.add(flat(handLayer(hand, 0.0, 7, 0.0f), 0.2));
  layers.add(flat(handLayer(hand, 0.0, 8, 0.0f), -0.2));
  EXPECT_GT(expectSameVisibility(layers.host, layers.store, hand, 0.25f, "hand-made"), 0);
}

// Hole counts on the store (GpuVisibility::holes) against countHoles, its
// host oracle: the same count for the layers of both sources and of one,
// one layer a source (holes behind the rim) and four, in views between
// the sources, with and without overlap.
TEST_F(GpuImageSlicerTest, HoleCountsAreTheHosts) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 120, 90, 9);
  auto sources = makeSourceLayerRenderer(scene);
  GpuVisibility visibility;
  long total = 0;
  for (int maxLayers : {1, 4}) {
    BothLayers both(*sources, cam, {cam.viewX(0), cam.viewX(8)}, maxLayers);
    const std::vector<SourceLayer>& host = both.host;
    const DeviceLayers& device = both.device;
    ASSERT_EQ(device.count(), int(host.size()));
    for (bool both : {true, false}) {
      std::vector<const SourceLayer*> used;
      std::vector<uint8_t> use;
      for (const SourceLayer& l : host) {
        use.push_back(both || l.eye.x == cam.viewX(0));
        if (use.back()) used.push_back(&l);
      }
      for (int view : {2, 4, 7})
        for (float overlap : {0.0f, 0.25f}) {
          const long expected = countHoles(used, cam, cam.viewX(view), overlap);
          test::expectSameDecisions(visibility.holes(device, use, cam, cam.viewX(view), overlap), expected,
                              long(cam.width()) * cam.height(),
                              std::to_string(maxLayers) + " layers, " + (both ? "both sources" : "one") +
                                  ", view " + std::to_string(view) + ", overlap " + std::to_string(overlap));
          total += expected;
        }
    }
  }
  EXPECT_GT(total, 100) << "the cup should leave holes between its ends";
}

}  // namespace
}  // namespace mvr
