#include "apps/render/job_phase.h"

#include "apps/render/split_output.h"
#include "mvr/frames/progress.h"
#include "mvr/timer.h"

namespace mvr::app {

std::vector<ShearingCamera> rendersOf(const ShearingCamera& rendered, const SplitOutput* split,
                                      const Supersampling& aa) {
  if (!split) return {rendered};
  std::vector<ShearingCamera> renders;
  for (const RenderShare& s : split->shares()) renders.push_back(rendered.withShare(sampleShare(s, aa)));
  return renders;
}

double renderPhase(MpiSession* mpi, Renderer& renderer, const std::vector<ShearingCamera>& renders,
                   FrameSink& sink, long views, const std::string& label, RenderStats& stats) {
  Stopwatch watch;
  double seconds = 0.0;
  inPhase(mpi, [&] {
    ProgressSink progress(sink, renders, views, label);
    for (const ShearingCamera& c : renders) renderer.render(c, progress, stats);
    progress.finish();
    seconds = watch.seconds();
  });
  return seconds;
}

}  // namespace mvr::app
