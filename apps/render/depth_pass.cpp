#include "apps/render/depth_pass.h"

#include <optional>

#include "apps/render/job_phase.h"
#include "apps/render/split_output.h"
#include "mvr/depth.h"
#include "mvr/frames/frame_chain.h"

namespace mvr::app {

namespace {

// Hands each view of the depth pass on as a depth map, from views packed
// one float a pixel.
class DepthSink final : public FrameSink {
 public:
  explicit DepthSink(ImageSetWriter& writer) : writer_(writer) {}
  void putView(int row, int view, const Image& packed) override { writer_.putDepth(row, view, unpackDepth(packed)); }
  void putEpi(int, int, const Image&) override { fail("--depth", "the depth pass reorders EPIs into views"); }

 private:
  ImageSetWriter& writer_;
};

}  // namespace

void renderDepth(const BackendOptions& backend, const Scene& scene, const ShearingCamera& cam,
                 ImageSetWriter& writer, const ReorderMemory& reorder, RenderStats& stats, MpiSession* mpi,
                 const JobSplit* split, const std::string& dir) {
  DepthColoring coloring;
  Scene depth;  // outlives the renderer, which may keep it
  std::unique_ptr<Renderer> renderer;
  inPhase(mpi, [&] {
    depth = depthScene(scene, cam, coloring);
    renderer = makeRenderer(backend, depth, PixelType::F32);
  });
  DepthSink depthSink(writer);
  std::optional<SplitOutput> out;
  FrameSink* sink = &depthSink;
  if (split)
    sink = &out.emplace(*mpi, cam, *split,
                        SplitOutputSpec{.rendered = renderer->order(), .type = kPackedDepth, .dir = dir,
                                        .reorder = reorder, .scratchName = ".mvr_split_depth"},
                        depthSink, nullptr)
                .sink();
  // The split job's output reorders itself; otherwise EPIs become views here.
  FrameChain chain({.sink = sink},
                   {.rendered = renderer->order(), .delivered = split ? renderer->order() : FrameOrder::View,
                    .width = cam.width(), .height = cam.height(), .views = cam.views(), .type = kPackedDepth,
                    .reorder = reorder, .depth = coloring});
  renderPhase(mpi, *renderer, rendersOf(cam, out ? &*out : nullptr, {}), chain.entry(),
              long(cam.views()) * cam.rows(), renderer->name() + ", depth", stats);
  if (out) inPhase(mpi, [&] { out->assemble(); });
}

}  // namespace mvr::app
