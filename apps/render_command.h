#pragma once
// `mvr render`: scene + camera + back end -> image set with manifest.
#include <memory>
#include <string>

#include "mvr/image.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"

namespace mvr::app {

extern const char* const kRenderHelp;
extern const char* const kStreamHelp;

// streamCommand: `mvr stream` (EPIs to --to) rather than `mvr render`.
int runRender(int argc, char** argv, bool streamCommand = false);

struct BackendChoice {
  std::string backend = "mvr";  // mvr | interp | svr | svr-layered | deferred
  std::string pst = "strip";    // quad | strip | exact | cpu (mvr and interp)
  std::string texture = "vector";  // vector | direct (mvr GL modes only)
  std::string acquire = "dual";    // center | dual | hierarchical (interp only)
  int maxLayers = 4;               // depth-peeled layers per source view (interp only)
  float coalesce = 0.0f;           // pixels a coalesced run may move a pixel (interp only)
  bool visibility = false;         // drop layer pixels hidden from the track (interp only)
  int budget = 9;                  // hierarchical: source views per row at most
  int splits = 0;                  // split views per highlight (interp only)
  float overlap = 0.25f;           // slice widening per side, pixels (interp only)
};

// The accuracy mode a back end uses unless told: interp's pixel slices have
// one colour each, so quad is exact for them; MVR's default is strip.
inline const char* defaultPst(const std::string& backend) {
  return backend == "interp" ? "quad" : "strip";
}

// Throws mvr::Error for unknown names. Needs a current GL context.
std::unique_ptr<Renderer> makeRenderer(const BackendChoice& choice, const Scene& scene,
                                       PixelType type);

}  // namespace mvr::app
