#pragma once
// Display transforms from linear HDR radiance to linear display values in
// [0, 1], before the output encoding (`--tonemap`): the formulas three.js
// uses, so that a file looks as it does there.
//   aces     ACES filmic: Stephen Hill's fit of the RRT and ODT, with
//            three.js's 1 / 0.6 brightening (its #19621).
//   agx      AgX: Filament's and Blender's, through Rec. 2020 primaries,
//            its log2 range [-12.47, 4.03] and the minimal sigmoid fit.
//   neutral  Khronos PBR Neutral: identity up to 0.76, then a soft
//            shoulder that keeps hue.
// none leaves values as they are (the encoding clamps them).
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace mvr {

enum class ToneMap { None, Aces, Agx, Neutral };
inline constexpr ToneMap kToneMaps[] = {ToneMap::None, ToneMap::Aces, ToneMap::Agx, ToneMap::Neutral};

std::optional<ToneMap> toneMapNamed(const std::string& name);  // "none", "aces", "agx", "neutral"
const char* toneMapName(ToneMap map);
glm::vec3 toneMap(ToneMap map, const glm::vec3& linear);

}  // namespace mvr
