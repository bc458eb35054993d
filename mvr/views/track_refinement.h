#pragma once
// Hierarchical acquisition's walk over a row's track, which interp and
// warp share: which views become sources beyond the track's two ends.
#include <deque>
#include <utility>

#include "mvr/camera.h"
#include "mvr/renderer.h"

namespace mvr {

// Breadth first over the track, so that a spent budget leaves the added
// views spread evenly: from sources at views 0 and N - 1, the view m
// halfway between two sources at views a and b becomes one where
// holes(a, b, m), the holes they leave in view m, exceed holeFraction of
// its pixels; add(m) appends it. `sources` counts those there are, at
// most `budget`.
template <class Holes, class Add>
void refineTrack(const ShearingCamera& cam, double holeFraction, int budget, int sources, RenderStats& stats,
                 Holes&& holes, Add&& add) {
  const double tolerance = holeFraction * cam.width() * cam.height();
  std::deque<std::pair<int, int>> todo{{0, cam.views() - 1}};  // view indices of two sources
  while (!todo.empty() && sources < budget) {
    const auto [a, b] = todo.front();
    todo.pop_front();
    if (b - a < 2) continue;
    const int m = (a + b) / 2;
    const long count = holes(a, b, m);
    stats.counters["hole_checks"] += 1;
    if (double(count) <= tolerance) continue;
    add(m);
    ++sources;
    todo.emplace_back(a, m);
    todo.emplace_back(m, b);
  }
}

}  // namespace mvr
