#include "apps/quilt_layout.h"

#include <cstdio>
#include <regex>

#include <nlohmann/json.hpp>

#include "mvr/error.h"

namespace mvr::app {

const std::vector<QuiltLayout>& quiltPresets() {
  static const std::vector<QuiltLayout> presets{
      {11, 6, "go", 4092, 4092, 0.0},
      {8, 6, "portrait", 3360, 3360, 0.75},
      {7, 7, "16-landscape", 5999, 5999, 16.0 / 9.0},
      {11, 6, "16-portrait", 5995, 6000, 0.0},
      {7, 7, "32-landscape", 8190, 8190, 16.0 / 9.0},
      {11, 6, "32-portrait", 8184, 8184, 0.0},
      {8, 9, "65", 8192, 8192, 0.0},
  };
  return presets;
}

QuiltLayout parseQuilt(const std::string& text) {
  if (text == "auto") return {};
  for (const QuiltLayout& p : quiltPresets())
    if (text == p.preset) return p;
  static const std::regex grid("([1-9][0-9]{0,4})[xX]([1-9][0-9]{0,4})");
  std::smatch m;
  if (std::regex_match(text, m, grid)) return {std::stoi(m[1]), std::stoi(m[2])};
  std::string names;
  for (const QuiltLayout& p : quiltPresets()) names += ", " + p.preset;
  fail("--quilt", "'" + text + "' is not auto, COLSxROWS (positive whole numbers) or a display (" + names.substr(2) +
                      ")");
}

std::string quiltMetadata(int views, int columns, int rows, double aspect) {
  char rounded[32];
  std::snprintf(rounded, sizeof rounded, "%.2f", aspect);
  return nlohmann::json{{"LKGNumViews", views},
                        {"LKGRows", rows},
                        {"LKGColumns", columns},
                        {"LKGAspect", std::stod(rounded)},
                        {"LKGType", "Image"}}
      .dump();
}

}  // namespace mvr::app
