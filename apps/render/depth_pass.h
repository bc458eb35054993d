#pragma once
// The depth maps of a set (--depth): the depth scene (mvr/depth.h) rendered
// in float by the same back end, its frames packed into depths as they
// come and reordered into views where the back end renders EPIs; in a split
// job each rank renders its shares of the colour pass, and the grid's EPIs
// meet in a scratch file of their own.
#include <string>

#include "apps/cli/job_split.h"
#include "mvr/backends/backend.h"
#include "mvr/frames/volume.h"
#include "mvr/images/image_set.h"

namespace mvr::app {

class MpiSession;

void renderDepth(const BackendOptions& backend, const Scene& scene, const ShearingCamera& camera,
                 ImageSetWriter& writer, const ReorderMemory& reorder, RenderStats& stats, MpiSession* mpi,
                 const JobSplit* split, const std::string& dir);

}  // namespace mvr::app
