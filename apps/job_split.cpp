#include "apps/job_split.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>

#include "slicing/slice_table.h"

namespace mvr::app {

int launchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

std::vector<double> scanlineCosts(const Scene& scene, const ShearingCamera& camera, int row) {
  const int h = camera.height();
  std::vector<float> y(scene.vertexCount());
  for (size_t i = 0; i < y.size(); ++i) y[i] = float(camera.project(scene.positions[i], 0, row).y);
  std::vector<double> slices(size_t(h) + 1, 0.0);  // differences, then counts
  for (const glm::uvec3& t : scene.triangles) {
    const auto [first, last] = scanlineRange(y[t.x], y[t.y], y[t.z], h);
    slices[size_t(first)] += 1.0;
    slices[size_t(last)] -= 1.0;
  }
  std::partial_sum(slices.begin(), slices.end(), slices.begin());
  slices.pop_back();
  const double fixed = std::max(1.0, std::accumulate(slices.begin(), slices.end(), 0.0) / h);
  for (double& c : slices) c += fixed;
  return slices;
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

JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks,
                  const std::vector<double>& costs) {
  JobSplit split;
  const RenderShare whole = camera.share();
  auto equal = [](int n) { return std::vector<double>(size_t(n), 1.0); };
  std::vector<IndexRange> parts;
  if (camera.rows() >= ranks) {
    split.axis = "rows";
    parts = splitByCost(equal(camera.rows()), ranks);
  } else if (order == FrameOrder::Epi) {
    split.axis = "scanlines";
    parts = splitByCost(costs.empty() ? equal(camera.height()) : costs, ranks);
  } else {
    split.axis = "views";
    parts = splitByCost(equal(camera.views()), ranks);
  }
  for (IndexRange part : parts) {
    RenderShare s = whole;
    (split.axis == "rows" ? s.rows : split.axis == "scanlines" ? s.scanlines : s.views) = part;
    split.shares.push_back(s);
  }
  return split;
}

}  // namespace mvr::app
