#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "mvr/camera.h"
#include "mvr/error.h"
#include "mvr/images/manifest.h"

#include <nlohmann/json.hpp>

namespace mvr {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("mvr_manifest_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Above 10,000 views the names need five digits; the pattern the manifest
// records must name exactly the files the set holds, and a reader must
// derive the same names from the manifest alone.
TEST(Manifest, ReaderNamesEveryOneOf10001Views) {
  const fs::path dir = freshDir("10001");
  Manifest written;
  written.views = 10001;
  written.width = 4;
  written.height = 2;
  written.write(dir.string());

  const Manifest read = Manifest::read(dir.string());
  ASSERT_EQ(read.views, 10001);
  EXPECT_EQ(read.toJson()["naming"], "view_%05d");
  std::set<std::string> names;
  std::string previous;
  for (int v = 0; v < read.views; ++v) {
    const std::string name = read.viewName(0, v);
    char expected[32];
    std::snprintf(expected, sizeof expected, "view_%05d.png", v);
    ASSERT_EQ(name, expected);
    ASSERT_LT(previous, name) << "names must sort in view order";
    previous = name;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), 10001u);
  EXPECT_EQ(read.viewName(0, 10000), "view_10000.png");
}

TEST(Manifest, TenThousandViewsKeepFourDigits) {
  Manifest m;
  m.views = 10000;
  EXPECT_EQ(m.viewPattern(), "view_%04d");
  EXPECT_EQ(m.viewName(0, 9999), "view_9999.png");
}

TEST(Manifest, GridAndEpiPatternsFollowTheirCounts) {
  Manifest m;
  m.views = 12, m.rows = 1001, m.height = 20000, m.format = "exr", m.order = "epi";
  EXPECT_EQ(m.viewPattern(), "view_r%04d_c%04d");
  EXPECT_EQ(m.viewName(1000, 11), "view_r1000_c0011.exr");
  EXPECT_EQ(m.epiName(3, 19999), "epi_r0003_19999.exr");
  EXPECT_EQ(m.toJson()["naming"], "epi_r%04d_%05d (rows: views)");
}

TEST(Manifest, RoundTripKeepsLayoutAndInfo) {
  const fs::path dir = freshDir("roundtrip");
  Manifest m;
  m.views = 7, m.rows = 2, m.width = 320, m.height = 240, m.format = "tiff", m.bits = 16;
  m.info["backend"] = "mvr";
  m.write(dir.string());
  EXPECT_FALSE(fs::exists(dir / "manifest.json.part"));
  const Manifest r = Manifest::read(dir.string());
  EXPECT_EQ(r.views, 7);
  EXPECT_EQ(r.rows, 2);
  EXPECT_EQ(r.width, 320);
  EXPECT_EQ(r.height, 240);
  EXPECT_EQ(r.format, "tiff");
  EXPECT_EQ(r.bits, 16);
  EXPECT_EQ(r.info["backend"], "mvr");
  EXPECT_FALSE(r.info.contains("naming"));
}

// Every view of a full-parallax grid is listed as a pinhole camera, one
// line each, with the camera's own K, V and eye, row by row.
TEST(Manifest, ListsEveryViewAsAPinholeCamera) {
  CameraSpec spec;
  spec.rowTop = 0.5, spec.rowBottom = -0.5;
  const ShearingCamera cam(spec, 32, 24, 4, 3);
  Manifest written;
  written.views = 4, written.rows = 3, written.width = 32, written.height = 24;
  written.setCamera(cam);
  const std::string text = written.text();
  const nlohmann::json j = nlohmann::json::parse(text);
  const nlohmann::json& views = j.at("cameras").at("views");
  ASSERT_EQ(views.size(), 12u);
  for (const nlohmann::json& v : views) {
    const int view = v.at("view"), row = v.at("row");
    const glm::dmat3 k = cam.intrinsics(view, row);
    const glm::dmat4 w = cam.worldToCamera(view, row);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(v.at("K")[r][c].get<double>(), k[c][r]);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(v.at("V")[r][c].get<double>(), w[c][r]);
    EXPECT_EQ(v.at("eye")[0].get<double>(), cam.eye(view, row).x);
    EXPECT_EQ(v.at("eye")[1].get<double>(), cam.eye(view, row).y);
  }
  EXPECT_EQ(views[5].at("row"), 1);  // row by row: view 1 of row 1
  EXPECT_EQ(views[5].at("view"), 1);
  size_t lines = 0;
  for (size_t at = text.find("\n      {\"K\""); at != std::string::npos; at = text.find("\n      {\"K\"", at + 1))
    ++lines;
  EXPECT_EQ(lines, 12u);
}

TEST(Manifest, BadManifestsNameTheFile) {
  const fs::path dir = freshDir("bad");
  auto readError = [&](const char* text) {
    if (text) std::ofstream(dir / "manifest.json") << text;
    try {
      Manifest::read(dir.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(readError("{").find("manifest.json: bad JSON"), std::string::npos);
  EXPECT_NE(readError(R"({"views": 0})").find("'views' must be an integer 1..65536"),
            std::string::npos);
  EXPECT_NE(readError(R"({"views": 2, "format": "gif"})").find("unknown format 'gif'"),
            std::string::npos);
  EXPECT_NE(readError(R"({"views": "2"})").find("manifest.json"), std::string::npos);
  fs::remove(dir / "manifest.json");
  EXPECT_NE(readError(nullptr).find("no manifest.json"), std::string::npos);
}

}  // namespace
}  // namespace mvr
