#include "apps/job_split.h"

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

double imbalance(const std::vector<double>& costs, const std::vector<IndexRange>& parts) {
  const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
  double largest = 0.0;
  for (IndexRange p : parts)
    largest = std::max(largest, std::accumulate(costs.begin() + p.begin, costs.begin() + p.end, 0.0));
  return total > 0.0 ? largest * double(parts.size()) / total : 1.0;
}

JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks, const std::vector<double>& costs) {
  auto equal = [](int n) { return std::vector<double>(size_t(n), 1.0); };
  const std::vector<double> rowCosts = equal(camera.rows());
  const std::vector<double> axisCosts =
      order == FrameOrder::View ? equal(camera.views()) : costs.empty() ? equal(camera.height()) : costs;
  // Whole rows when there are enough: no rank then needs another's frames
  // to reorder its rows, which at scale costs more than the balance lost
  // (docs/SCALING.md: 100 rows on 64 ranks). Otherwise every grid of a row
  // groups by b = ranks / a parts of a row; the best balanced wins, and of
  // equals the one with more row groups (fewer ranks repeat a row's work).
  JobSplit best;
  double bestBalance = INFINITY;
  for (int a = 1; a <= ranks; ++a) {
    if (ranks % a != 0 || a > camera.rows() || (camera.rows() >= ranks && a != ranks)) continue;
    const int b = ranks / a;
    const std::vector<IndexRange> rowParts = splitByCost(rowCosts, a), axisParts = splitByCost(axisCosts, b);
    const double balance = imbalance(rowCosts, rowParts) * imbalance(axisCosts, axisParts);
    if (balance > bestBalance * (1.0 + 1e-9)) continue;
    bestBalance = balance;
    best = JobSplit{order == FrameOrder::Epi ? "scanlines" : "views", a, b, balance, {}};
    for (IndexRange rows : rowParts)
      for (IndexRange part : axisParts) {
        RenderShare s = camera.share();
        s.rows = rows;
        (order == FrameOrder::Epi ? s.scanlines : s.views) = part;
        best.shares.push_back(s);
      }
  }
  return best;
}

}  // namespace mvr::app
