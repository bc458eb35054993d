#include "epi/epi_rasterizer.h"
#include "mvr/error.h"

namespace mvr {

PstMode parsePstMode(const std::string& name) {
  if (name == "quad") return PstMode::Quad;
  if (name == "strip") return PstMode::Strip;
  if (name == "exact") return PstMode::Exact;
  if (name == "cpu") return PstMode::Cpu;
  fail("--pst", "unknown mode '" + name + "' (expected quad, strip, exact or cpu)");
}

const char* pstModeName(PstMode mode) {
  switch (mode) {
    case PstMode::Quad: return "quad";
    case PstMode::Strip: return "strip";
    case PstMode::Exact: return "exact";
    case PstMode::Cpu: return "cpu";
  }
  return "?";
}

TextureMode parseTextureMode(const std::string& name) {
  if (name == "vector") return TextureMode::Vector;
  if (name == "direct") return TextureMode::Direct;
  fail("--texture", "unknown mode '" + name + "' (expected vector or direct)");
}

}  // namespace mvr
