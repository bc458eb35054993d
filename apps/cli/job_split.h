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
// This process's rank as the launcher's environment gives it, -1 where it
// does not; and how many of the job's ranks share this machine, 0 where
// the environment does not say.
int launchedRank();
int launchedLocalRanks();

// The estimated cost of each scanline's EPIs for an EPI renderer, in
// pixels of one view's row: the row itself (every EPI row is cleared and
// read back), and per triangle crossing it a slice's setup and the pixels
// its track covers (its width in the middle view).
std::vector<double> scanlineCosts(const Scene& scene, const ShearingCamera& camera, int row);

// Contiguous ranges of [0, costs.size()) with near-equal sums, one per part.
std::vector<IndexRange> splitByCost(const std::vector<double>& costs, int parts);

// Rank k's shares: first wholeRows whole rows of its own, rows
// [k * wholeRows, (k + 1) * wholeRows), then, when rows are left over
// (fewer than ranks), its cell of a grid over them: row group k / parts,
// part k % parts of each row (bands of scanlines for EPI renderers, runs
// of views for view renderers).
struct JobSplit {
  std::string axis;           // what a row is split by: "scanlines" or "views"
  int wholeRows = 0;          // rows each rank renders whole
  int rowGroups = 0, parts = 0;  // the grid over the rows left (0 x 0: none)
  double imbalance = 1.0;     // estimated: the costliest rank's work over the mean
  std::vector<std::vector<RenderShare>> shares;  // per rank, in render order

  int ranks() const { return int(shares.size()); }
  // The rows rendered whole, [0, gridBegin); the grid's, [gridBegin, rows).
  int gridBegin() const { return wholeRows * ranks(); }
};

// Whole rows, as many as every rank can have (no rank then needs another's
// frames to reorder them); the rows left over, fewer than the ranks, as a
// grid of row groups by parts of a row chosen for the best estimated
// balance, the parts bands of scanlines by cost (EPI renderers; equal
// bands without costs) or equal runs of views (view renderers).
JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks,
                  const std::vector<double>& scanlineCosts = {});

}  // namespace mvr::app
