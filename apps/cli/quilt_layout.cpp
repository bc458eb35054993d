#include "apps/cli/quilt_layout.h"

#include <cstdio>
#include <regex>

#include <nlohmann/json.hpp>

#include "mvr/error.h"
#include "mvr/images/image_file.h"

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

QuiltFile readQuiltLayout(const std::string& path, int imageWidth, int imageHeight) {
  static const std::regex name(".*_qs([1-9][0-9]{0,4})x([1-9][0-9]{0,4})a([0-9]+(\\.[0-9]+)?)\\.[A-Za-z0-9]+");
  const std::string comment = readImageAttribute(path, "Exif:UserComment");
  const auto exif = nlohmann::json::parse(comment.empty() ? "null" : comment, nullptr, /*allow_exceptions=*/false);
  auto exifInt = [&](const char* key) {
    return exif.is_object() && exif.contains(key) && exif[key].is_number_integer() ? exif[key].get<int>() : 0;
  };
  std::smatch m;
  QuiltFile q;
  if (std::regex_match(path, m, name)) {
    q = {std::stoi(m[1]), std::stoi(m[2]), 0, std::stod(m[3])};
  } else if (exifInt("LKGColumns") > 0 && exifInt("LKGRows") > 0) {  // the name lost, the metadata kept
    q = {exifInt("LKGColumns"), exifInt("LKGRows"), 0, 0.0};
    if (exif.contains("LKGAspect") && exif["LKGAspect"].is_number()) q.aspect = exif["LKGAspect"].get<double>();
  } else {
    fail(path, "not a quilt: neither a _qs{COLS}x{ROWS}a{ASPECT} name nor LKGColumns and LKGRows in its EXIF");
  }
  if (q.columns > 1024 || q.rows > 1024 || imageWidth % q.columns || imageHeight % q.rows)
    fail(path, std::to_string(imageWidth) + "x" + std::to_string(imageHeight) + " pixels do not divide into " +
                   std::to_string(q.columns) + "x" + std::to_string(q.rows) + " tiles");
  q.views = q.columns * q.rows;
  // The metadata may say fewer views (the last tiles empty).
  if (const int views = exifInt("LKGNumViews"); exif.is_object() && exif.contains("LKGNumViews")) {
    if (views < 1 || views > q.views) fail(path, "LKGNumViews " + std::to_string(views) + " does not fit the tiles");
    q.views = views;
  }
  return q;
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
