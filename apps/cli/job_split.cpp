#include "apps/cli/job_split.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "slicing/slice_table.h"

namespace mvr::app {
namespace {

// A slice's track costs about as much to set up as this many pixels to
// fill: 4 shares of the 143K teacup (mvr:cpu and mvr:strip, 640x480 x 100
// and 160x140 x 400 views; mvr bench --shares) balance within 1.03-1.10
// for 32 to 128, within 1.12-1.21 for 4 and 1.2-1.5 for 0 (docs/SCALING.md).
constexpr double kSliceSetupPixels = 64.0;

}  // namespace

int launchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

int launchedRank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
    if (const char* v = std::getenv(name)) return std::max(0, std::atoi(v));
  return -1;
}

int launchedLocalRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "PMI_LOCAL_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 0;
}

std::vector<double> scanlineCosts(const Scene& scene, const ShearingCamera& camera, int row) {
  const int h = camera.height();
  std::vector<glm::vec2> p(scene.vertexCount());  // the middle view's pixel positions
  for (size_t i = 0; i < p.size(); ++i) p[i] = glm::vec2(camera.project(scene.positions[i], camera.views() / 2, row));
  // Every EPI row is cleared and read back (its width), and each slice's
  // track costs a setup and the pixels it covers.
  std::vector<double> cost(size_t(h), double(camera.width()));
  for (const glm::uvec3& t : scene.triangles) {
    const glm::vec2 a = p[t.x], b = p[t.y], c = p[t.z];
    const auto [first, last] = scanlineRange(a.y, b.y, c.y, h);
    for (int j = first; j < last; ++j) {
      // The triangle's horizontal extent at the scanline's centre.
      const float y = float(j) + 0.5f;
      float lo = INFINITY, hi = -INFINITY;
      for (auto [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
        if ((y < std::min(u.y, v.y)) || (y > std::max(u.y, v.y)) || u.y == v.y) continue;
        const float x = u.x + (v.x - u.x) * (y - u.y) / (v.y - u.y);
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
      if (hi >= lo) cost[size_t(j)] += kSliceSetupPixels + double(hi - lo);
    }
  }
  return cost;
}

std::vector<IndexRange> splitByCost(const std::vector<double>& costs, int parts) {
  const int n = int(costs.size());
  std::vector<double> before(size_t(n) + 1, 0.0);
  std::partial_sum(costs.begin(), costs.end(), before.begin() + 1);
  std::vector<IndexRange> out;
  int begin = 0;
  for (int k = 0; k < parts; ++k) {
    // The first index whose cost before reaches part k + 1's share, but
    // never an empty part while items remain for the parts after it.
    const double target = before.back() * (k + 1) / parts;
    int end = int(std::lower_bound(before.begin(), before.end(), target) - before.begin());
    if (k + 1 == parts) end = n;
    const int lo = std::min(begin + 1, n), hi = std::max(lo, n - (parts - k - 1));
    end = std::clamp(end, lo, hi);
    out.push_back({begin, end});
    begin = end;
  }
  return out;
}

JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks, const std::vector<double>& costs) {
  auto equal = [](int n) { return std::vector<double>(size_t(n), 1.0); };
  const std::vector<double> axisCosts =
      order == FrameOrder::View ? equal(camera.views()) : costs.empty() ? equal(camera.height()) : costs;
  const double rowCost = std::accumulate(axisCosts.begin(), axisCosts.end(), 0.0);
  JobSplit best{order == FrameOrder::Epi ? "scanlines" : "views", camera.rows() / ranks, 0, 0, 1.0,
                std::vector<std::vector<RenderShare>>(size_t(ranks))};
  if (best.wholeRows > 0)
    for (int k = 0; k < ranks; ++k) {
      RenderShare s = camera.share();
      s.rows = {k * best.wholeRows, (k + 1) * best.wholeRows};
      best.shares[size_t(k)].push_back(s);
    }
  const int left = camera.rows() - best.gridBegin();
  if (left == 0) return best;
  // The rows left over, fewer than the ranks: every grid of a row groups
  // by b = ranks / a parts of a row. The one whose costliest rank costs
  // least wins, and of equals the one with more row groups (fewer ranks
  // repeat a row's fixed work).
  double bestLoad = INFINITY;
  std::vector<RenderShare> grid;
  for (int a = 1; a <= std::min(left, ranks); ++a) {
    if (ranks % a != 0) continue;
    const int b = ranks / a;
    const std::vector<IndexRange> rowParts = splitByCost(equal(left), a), axisParts = splitByCost(axisCosts, b);
    double load = 0.0;  // the costliest rank's, in rows
    for (IndexRange rows : rowParts)
      for (IndexRange part : axisParts)
        load = std::max(load, rows.size() * std::accumulate(axisCosts.begin() + part.begin,
                                                            axisCosts.begin() + part.end, 0.0) / rowCost);
    if (load > bestLoad * (1.0 + 1e-9)) continue;
    bestLoad = load;
    best.rowGroups = a;
    best.parts = b;
    grid.clear();
    for (IndexRange rows : rowParts)
      for (IndexRange part : axisParts) {
        RenderShare s = camera.share();
        s.rows = {best.gridBegin() + rows.begin, best.gridBegin() + rows.end};
        (order == FrameOrder::Epi ? s.scanlines : s.views) = part;
        grid.push_back(s);
      }
  }
  for (int k = 0; k < ranks; ++k) best.shares[size_t(k)].push_back(grid[size_t(k)]);
  best.imbalance = (best.wholeRows + bestLoad) * ranks / double(camera.rows());
  return best;
}

}  // namespace mvr::app
