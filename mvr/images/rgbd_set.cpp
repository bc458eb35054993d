#include "mvr/images/rgbd_set.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "mvr/error.h"
#include "mvr/images/image_file.h"
#include "mvr/images/manifest.h"

namespace mvr {
namespace fs = std::filesystem;

Image linearColor(const Image& image) {
  if (image.type == PixelType::F32) return image;
  Image out(image.width, image.height, PixelType::F32);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) out.setLinear(x, y, image.linear(x, y));
  return out;
}

namespace {

std::string path(const std::string& dir, const std::string& name) { return (fs::path(dir) / name).string(); }

// Depth must be finite and not negative (0: no sample); sizes must agree.
void checkReference(const RgbdView& r, const std::string& colorFile, const std::string& depthFile) {
  if (r.depth.width != r.color.width || r.depth.height != r.color.height)
    fail(depthFile, "depth is " + std::to_string(r.depth.width) + "x" + std::to_string(r.depth.height) + ", " +
                        colorFile + " is " + std::to_string(r.color.width) + "x" + std::to_string(r.color.height));
  for (int y = 0; y < r.depth.height; ++y)
    for (int x = 0; x < r.depth.width; ++x)
      if (const float z = r.depth.at(x, y); !std::isfinite(z) || z < 0.0f)
        fail(depthFile, "depth " + std::to_string(z) + " at pixel (" + std::to_string(x) + ", " +
                            std::to_string(y) + ") is not a finite distance");
}

RgbdView readReference(const std::string& colorFile, const std::string& depthFile) {
  if (!fs::exists(colorFile)) fail(colorFile, "missing colour image");
  if (!fs::exists(depthFile)) fail(depthFile, "missing depth map");
  RgbdView r;
  r.color = linearColor(readImage(colorFile));
  r.depth = readDepthImage(depthFile);
  checkReference(r, colorFile, depthFile);
  return r;
}

template <int N>
glm::mat<N, N, double> matrixFrom(const nlohmann::json& rows, const std::string& where) {
  glm::mat<N, N, double> m(1.0);
  if (!rows.is_array() || rows.size() != N) fail(where, "a camera matrix is not " + std::to_string(N) + " rows");
  for (int r = 0; r < N; ++r) {
    if (!rows[r].is_array() || rows[r].size() != N) fail(where, "a camera matrix row is not " + std::to_string(N) + " numbers");
    for (int c = 0; c < N; ++c) {
      if (!rows[r][c].is_number()) fail(where, "a camera matrix entry is not a number");
      m[c][r] = rows[r][c].get<double>();
    }
  }
  return m;
}

RgbdSet loadMvrSet(const std::string& dir) {
  const Manifest m = Manifest::read(dir);
  const std::string where = path(dir, "manifest.json");
  if (m.order != "view") fail(where, "an EPI-ordered set has no views to warp");
  if (!m.info.contains("depth")) fail(where, "the set has no depth maps (render it with --depth)");
  const nlohmann::json& cameras = m.info.value("cameras", nlohmann::json::object());
  const nlohmann::json& list = cameras.value("views", nlohmann::json::array());
  if (!list.is_array() || list.size() != size_t(m.views) * m.rows) fail(where, "the cameras do not list every view");
  const nlohmann::json& c = m.info.value("camera", nlohmann::json::object());
  RgbdSet set{"mvr", m.width, m.height, m.views, m.rows};
  try {
    set.camera.distance = c.at("distance").get<double>();
    set.camera.planeWidth = c.at("image_plane").at(0).get<double>();
    set.camera.planeHeight = c.at("image_plane").at(1).get<double>();
    set.camera.trackLeft = c.at("track").at(0).get<double>();
    set.camera.trackRight = c.at("track").at(1).get<double>();
    if (c.contains("row_y")) {
      set.camera.rowTop = set.camera.rowBottom = c.at("row_y").get<double>();
    } else {
      set.camera.rowTop = c.at("rows_track").at(0).get<double>();
      set.camera.rowBottom = c.at("rows_track").at(1).get<double>();
    }
    set.camera.nearDistance = c.at("near").get<double>();
    set.camera.farDistance = c.at("far").get<double>();
  } catch (const nlohmann::json::exception&) {
    fail(where, "the camera block is incomplete");
  }
  // V in the rig's coordinates, whose image plane is z = 0 (render --focal
  // records its plane's z and V in the scene's).
  const double planeZ = c.value("image_plane_z", 0.0);
  const glm::dmat4 toScene = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, planeZ));
  for (const nlohmann::json& v : list) {
    const int row = v.value("row", -1), view = v.value("view", -1);
    if (row < 0 || row >= m.rows || view < 0 || view >= m.views) fail(where, "a camera names no view of the set");
    RgbdView r = readReference(path(dir, m.viewName(row, view)), path(dir, m.depthName(row, view)));
    r.K = matrixFrom<3>(v.value("K", nlohmann::json()), where);
    r.V = matrixFrom<4>(v.value("V", nlohmann::json()), where) * toScene;
    set.references.push_back(std::move(r));
  }
  return set;
}

// parameters.cfg: [section] lines and key = value lines; # and ; comments.
using Config = std::map<std::string, std::string>;  // "section.key" -> value

Config readConfig(const std::string& file) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot read");
  Config config;
  std::string line, section;
  auto trim = [](std::string s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  for (int number = 1; std::getline(in, line); ++number) {
    line = trim(line);
    if (line.empty() || line[0] == '#' || line[0] == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']') fail(file, "line " + std::to_string(number) + ": unterminated section");
      section = trim(line.substr(1, line.size() - 2));
      continue;
    }
    const size_t eq = line.find_first_of("=:");
    if (eq == std::string::npos) fail(file, "line " + std::to_string(number) + ": expected key = value");
    config[section + "." + trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
  }
  return config;
}

double number(const Config& config, const std::string& key, const std::string& file) {
  const auto it = config.find(key);
  if (it == config.end()) fail(file, "missing " + key);
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !std::isfinite(v)) fail(file, key + " = '" + it->second + "' is not a number");
  return v;
}

std::string camName(const char* pattern, int index) {
  char buf[64];
  std::snprintf(buf, sizeof buf, pattern, index);
  return buf;
}

RgbdSet loadHciSet(const std::string& dir) {
  const std::string file = path(dir, "parameters.cfg");
  const Config cfg = readConfig(file);
  auto integer = [&](const std::string& key, int lo, int hi) {
    const double v = number(cfg, key, file);
    if (v != std::floor(v) || v < lo || v > hi)
      fail(file, key + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi));
    return int(v);
  };
  RgbdSet set{"hci"};
  set.width = integer("intrinsics.image_resolution_x_px", 1, Limits::kMaxSide);
  set.height = integer("intrinsics.image_resolution_y_px", 1, Limits::kMaxSide);
  set.views = integer("extrinsics.num_cams_x", 1, Limits::kMaxViews);
  set.rows = integer("extrinsics.num_cams_y", 1, Limits::kMaxRows);
  const double focalMm = number(cfg, "intrinsics.focal_length_mm", file);
  const double sensorMm = number(cfg, "intrinsics.sensor_size_mm", file);
  const double baseline = number(cfg, "extrinsics.baseline_mm", file) / 1000.0;
  const double focus = number(cfg, "extrinsics.focus_distance_m", file);
  if (!(focalMm > 0 && sensorMm > 0 && baseline > 0 && focus > 0))
    fail(file, "focal length, sensor size, baseline and focus distance must be positive");
  // Pixel focal length f W / S, so the image plane at the focus distance is
  // W F / f wide: our shearing camera with D = F.
  const double fx = focalMm / sensorMm * std::max(set.width, set.height);
  CameraSpec& c = set.camera;
  c.distance = focus;
  c.planeWidth = set.width * focus / fx;
  c.planeHeight = set.height * focus / fx;
  c.trackLeft = -0.5 * (set.views - 1) * baseline;
  c.trackRight = -c.trackLeft;
  c.rowTop = 0.5 * (set.rows - 1) * baseline;
  c.rowBottom = -c.rowTop;
  const ShearingCamera grid(c, set.width, set.height, set.views, set.rows);
  float nearest = INFINITY, farthest = 0.0f;
  auto add = [&](int index, const std::string& depthName) {
    const int row = index / set.views, column = index % set.views;
    RgbdView r = readReference(path(dir, camName("input_Cam%03d.png", index)), path(dir, depthName));
    r.K = grid.intrinsics(column, row);
    r.V = grid.worldToCamera(column, row);
    for (float z : r.depth.values)
      if (z > 0.0f) nearest = std::min(nearest, z), farthest = std::max(farthest, z);
    set.references.push_back(std::move(r));
  };
  for (int i = 0; i < set.views * set.rows; ++i)
    if (fs::exists(path(dir, camName("gt_depth_lowres_Cam%03d.pfm", i)))) add(i, camName("gt_depth_lowres_Cam%03d.pfm", i));
  if (set.references.empty()) {
    if (!fs::exists(path(dir, "gt_depth_lowres.pfm")))
      fail(dir, "no depth maps (gt_depth_lowres_Cam%03d.pfm or gt_depth_lowres.pfm)");
    add((set.rows / 2) * set.views + set.views / 2, "gt_depth_lowres.pfm");
  }
  if (!(farthest > 0.0f)) fail(dir, "every depth map is empty");
  c.nearDistance = 0.5 * nearest;
  c.farDistance = 2.0 * farthest;
  return set;
}

}  // namespace

RgbdSet loadRgbdSet(const std::string& dir) {
  if (!fs::is_directory(dir)) fail(dir, "not a folder");
  if (fs::exists(fs::path(dir) / "manifest.json")) return loadMvrSet(dir);
  if (fs::exists(fs::path(dir) / "parameters.cfg")) return loadHciSet(dir);
  fail(dir, "neither an mvr set (manifest.json) nor the HCI layout (parameters.cfg)");
}

}  // namespace mvr
