#pragma once
// How a render splits over the K processes of an MPI job (Halle 9.5: once
// the geometry is transformed, every scanline's EPIs are independent, and
// full-parallax rows are independent sequences). Pure arithmetic, the same
// on every rank, so no rank has to ask another for its share.
#include <string>
#include <vector>

#include "mvr/camera.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr::app {

// The ranks mpirun (Open MPI, MPICH or another PMI launcher) says this
// process is one of, read from the environment without initialising MPI;
// 1 when not started by a launcher.
int launchedRanks();

// The estimated cost of each scanline's EPIs for an EPI renderer, in
// pixels of one view's row: the row itself (every EPI row is cleared and
// read back), and per triangle crossing it a slice's setup and the pixels
// its track covers (its width in the middle view).
std::vector<double> scanlineCosts(const Scene& scene, const ShearingCamera& camera, int row);

// Contiguous ranges of [0, costs.size()) with near-equal sums, one per part.
std::vector<IndexRange> splitByCost(const std::vector<double>& costs, int parts);

// Rank k's share: row group k / parts, part k % parts of each row (bands
// of scanlines for EPI renderers, runs of views for view renderers).
struct JobSplit {
  std::string axis;           // what a row is split by: "scanlines" or "views"
  int rowGroups = 1, parts = 1;  // rowGroups x parts = ranks
  double imbalance = 1.0;     // estimated: the costliest share over the mean share
  std::vector<RenderShare> shares;  // one per rank
};

// The costliest part's cost over the mean part's.
double imbalance(const std::vector<double>& costs, const std::vector<IndexRange>& parts);

// Whole rows per rank when there are at least as many rows as ranks;
// otherwise a grid of row groups by parts of a row chosen for the best
// estimated balance, the parts bands of scanlines by cost (EPI renderers;
// equal bands without costs) or equal runs of views (view renderers).
JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks,
                  const std::vector<double>& scanlineCosts = {});

}  // namespace mvr::app
