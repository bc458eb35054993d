#include "mvr/images/manifest.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/files/atomic_file.h"

namespace mvr {
namespace fs = std::filesystem;

namespace {

// Digits for indices 0..count-1: at least `least`, more when count needs.
int digitsFor(int count, int least) {
  int digits = 1;
  for (int n = count - 1; n >= 10; n /= 10) ++digits;
  return std::max(least, digits);
}

std::string printInts(const std::string& pattern, int a, int b = 0) {
  char buf[96];
  std::snprintf(buf, sizeof buf, pattern.c_str(), a, b);
  return buf;
}

std::string field(int digits) { return "%0" + std::to_string(digits) + "d"; }

}  // namespace

std::string Manifest::viewPattern() const {
  const std::string view = field(digitsFor(views, 4));
  return rows == 1 ? "view_" + view : "view_r" + field(digitsFor(rows, 3)) + "_c" + view;
}

std::string Manifest::epiPattern() const {
  const std::string scanline = field(digitsFor(height, 4));
  return rows == 1 ? "epi_" + scanline : "epi_r" + field(digitsFor(rows, 3)) + "_" + scanline;
}

std::string Manifest::depthPattern() const { return "depth" + viewPattern().substr(4); }

std::string Manifest::viewName(int row, int view) const {
  const std::string name = rows == 1 ? printInts(viewPattern(), view) : printInts(viewPattern(), row, view);
  return name + "." + format;
}

std::string Manifest::depthName(int row, int view) const {
  const std::string name = rows == 1 ? printInts(depthPattern(), view) : printInts(depthPattern(), row, view);
  return name + ".exr";
}

std::string Manifest::epiName(int row, int scanline) const {
  const std::string name =
      rows == 1 ? printInts(epiPattern(), scanline) : printInts(epiPattern(), row, scanline);
  return name + "." + format;
}

void Manifest::setCamera(const ShearingCamera& cam, double imagePlaneZ, const glm::dmat4& fromFile) {
  const CameraSpec& s = cam.spec();
  const double degrees = 180.0 / 3.14159265358979323846;
  info["camera"] = {{"distance", s.distance},
                    {"image_plane_z", imagePlaneZ},
                    {"cone_deg", 2.0 * std::atan(0.5 * std::abs(s.trackRight - s.trackLeft) / s.distance) * degrees},
                    {"fov_deg", 2.0 * std::atan(0.5 * cam.planeWidth() / s.distance) * degrees},
                    {"image_plane", {cam.planeWidth(), cam.planeHeight()}},
                    {"track", {s.trackLeft, s.trackRight}},
                    {"near", s.nearDistance},
                    {"far", s.farDistance},
                    {"view_spacing", cam.viewSpacing()},
                    {"units", "the scene's world units"},
                    {"axes", "world x right, y up, z toward the viewer; views look along -z from the "
                             "camera plane z = image_plane_z + distance to the image plane z = "
                             "image_plane_z"}};
  // One row has one camera y, not a track.
  if (cam.rows() > 1) info["camera"]["rows_track"] = {s.rowTop, s.rowBottom};
  else info["camera"]["row_y"] = cam.rowY(0);
  // The rig renders with its image plane at z = 0 (the scene moved by
  // -imagePlaneZ); V and the eyes are given in the scene's own coordinates.
  const glm::dmat4 toRig = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, -imagePlaneZ));
  // Every view as a pinhole camera (ShearingCamera::intrinsics and
  // worldToCamera), matrices row by row.
  nlohmann::json list = nlohmann::json::array();
  for (int row = 0; row < cam.rows(); ++row)
    for (int view = 0; view < cam.views(); ++view) {
      const glm::dmat3 k = cam.intrinsics(view, row);
      const glm::dmat4 v = cam.worldToCamera(view, row) * toRig;
      const glm::dvec3 e = cam.eye(view, row) + glm::dvec3(0.0, 0.0, imagePlaneZ);
      nlohmann::json kRows = nlohmann::json::array(), vRows = nlohmann::json::array();
      for (int r = 0; r < 3; ++r) kRows.push_back({k[0][r], k[1][r], k[2][r]});
      for (int r = 0; r < 4; ++r) vRows.push_back({v[0][r], v[1][r], v[2][r], v[3][r]});
      list.push_back({{"view", view}, {"row", row}, {"eye", {e.x, e.y, e.z}}, {"K", kRows}, {"V", vRows}});
    }
  info["cameras"] = {{"convention", "V: world to camera, camera x right, y down, z along the view (OpenCV's "
                                    "axes), world units; K: camera to pixels, x right, y down from the "
                                    "top-left corner, centre of pixel (i, j) at (i + 0.5, j + 0.5) "
                                    "(subtract 0.5 from K's cx and cy for integer pixel centres)"},
                     {"views", std::move(list)}};
  if (fromFile != glm::dmat4(1.0)) {
    nlohmann::json rows = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) rows.push_back({fromFile[0][r], fromFile[1][r], fromFile[2][r], fromFile[3][r]});
    info["cameras"]["from_file"] = rows;
    info["cameras"]["from_file_means"] =
        "the scene file's coordinates to the ones V and the eyes are in, row by row (a mesh file is centred on "
        "its bounds, --camera moves the scene into that camera's view): V * from_file takes the file's points";
  }
}

nlohmann::json Manifest::toJson() const {
  nlohmann::json j = info;
  j["views"] = views;
  j["rows"] = rows;
  j["width"] = width;
  j["height"] = height;
  j["format"] = format;
  j["order"] = order;
  j["bits"] = bits;
  j["color_encoding"] = colorEncoding();
  if (format == "png") j["png_compression"] = compression;
  else j["codec"] = codec.empty() ? defaultCodec(format) : codec;
  j["naming"] = order == "view" ? viewPattern() : epiPattern() + " (rows: views)";
  return j;
}

Manifest Manifest::fromJson(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) fail(where, "not a JSON object");
  Manifest m;
  auto number = [&](const char* key, int fallback, int lo, int hi) {
    const nlohmann::json v = j.value(key, nlohmann::json(fallback));
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      fail(where, std::string("'") + key + "' must be an integer " + std::to_string(lo) + ".." +
                      std::to_string(hi));
    return v.get<int>();
  };
  auto text = [&](const char* key, const char* fallback) {
    const nlohmann::json v = j.value(key, nlohmann::json(fallback));
    if (!v.is_string()) fail(where, std::string("'") + key + "' must be a string");
    return v.get<std::string>();
  };
  m.views = number("views", 0, 1, Limits::kMaxViews);
  m.rows = number("rows", 1, 1, Limits::kMaxRows);
  m.width = number("width", 0, 0, Limits::kMaxSide);
  m.height = number("height", 0, 0, Limits::kMaxSide);
  m.bits = number("bits", 8, 8, 32);
  m.compression = number("png_compression", kDefaultPngCompression, 0, 9);
  m.format = text("format", "png");
  m.codec = text("codec", "");
  m.order = text("order", "view");
  const std::string color = text("color_encoding", "linear");
  if (color != "srgb" && color != "linear") fail(where, "unknown color_encoding '" + color + "'");
  m.srgb = color == "srgb";
  if (m.format != "png" && m.format != "exr" && m.format != "tiff")
    fail(where, "unknown format '" + m.format + "'");
  if (m.order != "view" && m.order != "epi") fail(where, "unknown order '" + m.order + "'");
  m.info = j;
  for (const char* key : {"views", "rows", "width", "height", "format", "order", "bits", "png_compression",
                          "codec", "color_encoding", "naming"})
    m.info.erase(key);
  return m;
}

Manifest Manifest::read(const std::string& dir) {
  const fs::path path = fs::path(dir) / "manifest.json";
  if (!fs::exists(path)) fail(dir, "no manifest.json (not a finished image set)");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(std::ifstream(path));
  } catch (const nlohmann::json::exception& e) {
    fail(path.string(), std::string("bad JSON: ") + e.what());
  }
  return fromJson(j, path.string());
}

// Indented, but one line per view camera: ~210 bytes a view instead of
// ~820, which matters at thousands of views.
std::string Manifest::text() const {
  nlohmann::json j = toJson();
  nlohmann::json* views = j.contains("cameras") ? &j["cameras"]["views"] : nullptr;
  if (!views || views->empty()) return j.dump(2) + "\n";
  const nlohmann::json list = std::exchange(*views, "@views@");
  std::string lines = "[";
  for (size_t i = 0; i < list.size(); ++i) lines += (i ? ",\n      " : "\n      ") + list[i].dump();
  lines += "\n    ]";
  std::string text = j.dump(2) + "\n";
  return text.replace(text.find("\"@views@\""), 9, lines);
}

void Manifest::write(const std::string& dir) const {
  const std::string text = this->text();
  writeFileAtomically((fs::path(dir) / "manifest.json").string(), std::as_bytes(std::span(text)));
}

}  // namespace mvr
