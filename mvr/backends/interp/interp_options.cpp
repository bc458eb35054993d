#include "mvr/backends/interp/interp_options.h"

#include <cmath>

#include "mvr/error.h"

namespace mvr {

void validate(const InterpOptions& options) {
  if (options.maxLayers < 1 || options.maxLayers > 64) fail("--max-layers", "must be 1 to 64");
  if (!(options.coalesce >= 0.0f) || !std::isfinite(options.coalesce))
    fail("--coalesce", "must be a finite number of pixels, at least 0");
  if (options.budget < 2 || options.budget > 1024) fail("--budget", "must be 2 to 1024 source views");
  if (options.splits < 0 || options.splits > 64) fail("--splits", "must be 0 to 64");
  if (!(options.overlap >= 0.0f && options.overlap <= 4.0f)) fail("--overlap", "must be 0 to 4 pixels");
  if (options.outlineSamples < 1 || options.outlineSamples > 16) fail("--outline-samples", "must be 1 to 16");
}

}  // namespace mvr
