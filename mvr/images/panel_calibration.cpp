#include "mvr/images/panel_calibration.h"

#include <cmath>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr {

namespace {

// A field's number: the value itself, or its {"value": number}.
std::optional<double> number(const nlohmann::json& json, const char* key, const std::string& source) {
  const auto it = json.find(key);
  if (it == json.end()) return std::nullopt;
  const nlohmann::json& v = it->is_object() && it->contains("value") ? (*it)["value"] : *it;
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    fail(source, std::string("calibration field ") + key + " is not a finite number");
  return v.get<double>();
}

double required(const nlohmann::json& json, const char* key, const std::string& source) {
  const std::optional<double> v = number(json, key, source);
  if (!v) fail(source, std::string("calibration has no ") + key);
  return *v;
}

int pixels(const nlohmann::json& json, const char* key, const std::string& source) {
  const double v = required(json, key, source);
  if (!(v >= 1.0 && v <= 16384.0) || v != std::floor(v))
    fail(source, std::string("calibration ") + key + " must be a whole number of pixels, 1 to 16384");
  return int(v);
}

}  // namespace

PanelCalibration parseCalibration(const nlohmann::json& json, const std::string& source) {
  if (!json.is_object()) fail(source, "a calibration must be a JSON object (visual.json)");
  PanelCalibration c;
  c.pitch = required(json, "pitch", source);
  c.slope = required(json, "slope", source);
  c.center = required(json, "center", source);
  c.dpi = required(json, "DPI", source);
  c.screenW = pixels(json, "screenW", source);
  c.screenH = pixels(json, "screenH", source);
  c.invView = required(json, "invView", source) != 0.0;
  c.flipSubp = number(json, "flipSubp", source).value_or(0.0) != 0.0;
  c.flipImageX = number(json, "flipImageX", source).value_or(0.0) != 0.0;
  c.flipImageY = number(json, "flipImageY", source).value_or(0.0) != 0.0;
  c.viewCone = number(json, "viewCone", source).value_or(40.0);
  if (c.dpi <= 0.0) fail(source, "calibration DPI must be above 0");
  if (c.slope == 0.0) fail(source, "calibration slope must not be 0");
  if (c.pitch <= 0.0) fail(source, "calibration pitch must be above 0");
  if (!(c.viewCone > 0.0 && c.viewCone < 180.0)) fail(source, "calibration viewCone must be between 0 and 180 degrees");
  return c;
}

PanelCalibration readCalibration(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open the calibration");
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (json.is_discarded()) fail(path, "the calibration is not JSON");
  return parseCalibration(json, path);
}

}  // namespace mvr
