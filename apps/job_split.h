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

// The estimated cost of each scanline's EPIs for an EPI renderer: the
// slices the scene's triangles leave on it (their y range is the same in
// every view of a row) plus a fixed part, the EPI's clear, readback and
// hand-over, counted as the average scanline's slices (docs/SCALING.md).
std::vector<double> scanlineCosts(const Scene& scene, const ShearingCamera& camera, int row);

// Contiguous ranges of [0, costs.size()) with near-equal sums, one per part.
std::vector<IndexRange> splitByCost(const std::vector<double>& costs, int parts);

struct JobSplit {
  std::string axis;  // "rows", "scanlines" or "views"
  std::vector<RenderShare> shares;  // one per rank
};

// Whole rows when there are at least as many rows as ranks; otherwise
// bands of scanlines by cost (EPI renderers; equal bands without costs) or
// equal runs of views (view renderers).
JobSplit splitJob(const ShearingCamera& camera, FrameOrder order, int ranks,
                  const std::vector<double>& scanlineCosts = {});

}  // namespace mvr::app
