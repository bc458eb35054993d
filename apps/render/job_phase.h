#pragma once
// The phases of a job that may be split over MPI ranks: what runs on every
// rank, and how the ranks learn that one of them failed.
#include <string>
#include <vector>

#include "apps/render/mpi_session.h"
#include "mvr/error.h"
#include "mvr/frames/supersampling.h"
#include "mvr/renderer.h"

namespace mvr::app {

class SplitOutput;

// Runs one phase of the job. In a split job (mpi not null) every rank
// reaches the agreement however its phase ended; when any failed, the
// lowest failing rank has printed its error and every rank stops.
template <class Phase>
void inPhase(MpiSession* mpi, Phase&& phase) {
  if (!mpi) return phase();
  std::string error;
  try {
    phase();
  } catch (const Error& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = std::string("internal error: ") + e.what();
  }
  if (!mpi->agree(error)) throw JobFailed{};
}

// The cameras this process renders: a split job's shares (their samples
// under anti-aliasing), or the whole set.
std::vector<ShearingCamera> rendersOf(const ShearingCamera& rendered, const SplitOutput* split,
                                      const Supersampling& aa);

// Renders them into `sink` with progress over the set's `views`, as one
// phase of the job; returns the seconds this process rendered.
double renderPhase(MpiSession* mpi, Renderer& renderer, const std::vector<ShearingCamera>& renders,
                   FrameSink& sink, long views, const std::string& label, RenderStats& stats);

}  // namespace mvr::app
