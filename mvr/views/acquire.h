#pragma once
// How interp and warp choose their source views along the track.
#include <string>

#include "mvr/names.h"

namespace mvr {

// Where the source views come from:
//   center        the middle of the track, depth peeled
//   dual          both ends of the track, each depth peeled
//   hierarchical  both ends, then the view halfway between two sources
//                 wherever those two leave disocclusion holes there,
//                 recursively, until none does or the budget is spent
enum class Acquire { Center, Dual, Hierarchical };
inline constexpr NameTable<Acquire, 3> kAcquireNames{
    {{Acquire::Center, "center"}, {Acquire::Dual, "dual"}, {Acquire::Hierarchical, "hierarchical"}}};
inline Acquire parseAcquire(const std::string& name) {  // throws on unknown
  return parseName(kAcquireNames, name, "--acquire", "acquisition");
}
inline const char* acquireName(Acquire acquire) { return nameOf(kAcquireNames, acquire); }

}  // namespace mvr
