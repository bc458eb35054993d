#pragma once
// A lenticular display's calibration file (Looking Glass's visual.json):
// each field a number or {"value": number}.
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "mvr/lenticular.h"

namespace mvr {

// Throws mvr::Error naming `source` and the field: a missing one (pitch,
// slope, center, DPI, screenW, screenH, invView; the flips and viewCone
// may be absent), one that is not a finite number, zero or negative DPI
// or pitch, zero slope, a panel size outside 1..16384.
PanelCalibration parseCalibration(const nlohmann::json& json, const std::string& source);
PanelCalibration readCalibration(const std::string& path);

}  // namespace mvr
