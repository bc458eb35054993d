// RGB-D sets in (mvr/images/rgbd_set.h): a set mvr render --depth wrote, the
// HCI 4D light-field layout on a small generated fixture, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "mvr/error.h"
#include "mvr/images/rgbd_set.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("mvr_rgbd_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A PFM file as the format says: "Pf", size, a negative scale for
// little-endian floats, rows bottom to top.
void writePfm(const DepthImage& d, const fs::path& file) {
  std::ofstream out(file, std::ios::binary);
  out << "Pf\n" << d.width << " " << d.height << "\n-1.0\n";
  for (int y = d.height - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(&d.values[size_t(y) * d.width]), std::streamsize(d.width * sizeof(float)));
}

// Three views of the bundled scene with depth, rendered by svr.
fs::path renderedSet(const std::string& name, const std::string& extra = "") {
  const fs::path d = freshDir(name);
  const test::CliResult r = test::shell(test::mvrBinary() + " render --backend svr --views 3 --size 48x36 --depth " +
                                        extra + " --out " + (d / "set").string() + " >/dev/null");
  EXPECT_TRUE(test::succeeded(r));
  return d / "set";
}

TEST(RgbdSet, ReadsASetRenderedWithDepth) {
  const RgbdSet set = loadRgbdSet(renderedSet("mvr").string());
  EXPECT_EQ(set.layout, "mvr");
  EXPECT_EQ(set.width, 48);
  EXPECT_EQ(set.views, 3);
  ASSERT_EQ(set.references.size(), 3u);
  const RgbdView& r = set.references[2];
  EXPECT_EQ(r.color.type, PixelType::F32);
  EXPECT_EQ(r.depth.width, 48);
  // V puts the eye at the origin: the centre is view 2's eye on the track.
  EXPECT_NEAR(r.center().x, set.camera.trackRight, 1e-9);
  EXPECT_NEAR(r.center().z, set.camera.distance, 1e-9);
  EXPECT_NEAR(r.K[2][0], 24.0 + 48.0 / set.camera.planeWidth * set.camera.trackRight, 1e-9);
  float covered = 0;
  for (float z : r.depth.values) covered += z > 0.0f;
  EXPECT_GT(covered, 100.0f);
}

// The same three cameras described the HCI way: focus distance D, a pixel
// focal length W D / Wp (sensor 36 mm), baseline the view spacing; depth
// as PFM. The reader must give back the same K, V and depth, top row
// first.
TEST(RgbdSet, ReadsTheHciLayout) {
  const fs::path source = renderedSet("hci_source");
  const RgbdSet mvrSet = loadRgbdSet(source.string());
  const fs::path d = freshDir("hci");
  const CameraSpec& c = mvrSet.camera;
  const double fxPx = 48.0 * c.distance / c.planeWidth;
  std::ofstream(d / "parameters.cfg") << "[intrinsics]\nimage_resolution_x_px = 48\nimage_resolution_y_px = 36\n"
                                      << "focal_length_mm = " << fxPx * 36.0 / 48.0 << "\nsensor_size_mm = 36\n"
                                      << "fstop = 100\n\n[extrinsics]\nnum_cams_x = 3\nnum_cams_y = 1\n"
                                      << "baseline_mm = " << (c.trackRight - c.trackLeft) / 2 * 1000.0 << "\n"
                                      << "focus_distance_m = " << c.distance << "\n; a comment\n";
  for (int i = 0; i < 3; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    fs::copy_file(source / name, d / ("input_Cam00" + std::to_string(i) + ".png"));
    writePfm(mvrSet.references[i].depth, d / ("gt_depth_lowres_Cam00" + std::to_string(i) + ".pfm"));
  }
  const RgbdSet hci = loadRgbdSet(d.string());
  EXPECT_EQ(hci.layout, "hci");
  ASSERT_EQ(hci.references.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const RgbdView &a = mvrSet.references[i], &b = hci.references[i];
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) EXPECT_NEAR(a.K[col][row], b.K[col][row], 1e-6) << i;
    if (std::abs(c.trackLeft + c.trackRight) < 1e-12) {  // the HCI grid is centred on the axis
      for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) EXPECT_NEAR(a.V[col][row], b.V[col][row], 1e-9) << i;
    }
    EXPECT_EQ(a.depth.values, b.depth.values) << i;  // bit for bit, rows in order
    EXPECT_EQ(a.color.bytes, b.color.bytes) << i;
  }
  // Only the centre camera's depth: one reference, camera 1.
  for (int i = 0; i < 3; ++i) fs::remove(d / ("gt_depth_lowres_Cam00" + std::to_string(i) + ".pfm"));
  writePfm(mvrSet.references[1].depth, d / "gt_depth_lowres.pfm");
  const RgbdSet centre = loadRgbdSet(d.string());
  ASSERT_EQ(centre.references.size(), 1u);
  EXPECT_NEAR(centre.references[0].center().x, 0.0, 1e-12);
}

std::string errorOf(const fs::path& dir) {
  try {
    loadRgbdSet(dir.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RgbdSet, BadInputNamesTheFileAndProblem) {
  // No depth in the set; a missing depth file; a depth map of another size.
  const fs::path plain = freshDir("plain");
  test::shell(test::mvrBinary() + " render --backend svr --views 2 --size 16x12 --out " + plain.string());
  EXPECT_NE(errorOf(plain).find("render it with --depth"), std::string::npos) << errorOf(plain);
  const fs::path set = renderedSet("broken");
  fs::remove(set / "depth_0001.exr");
  EXPECT_NE(errorOf(set).find("depth_0001.exr: missing depth map"), std::string::npos) << errorOf(set);

  const fs::path hci = freshDir("hci_bad");
  std::ofstream(hci / "parameters.cfg") << "[intrinsics]\nimage_resolution_x_px = 4\nimage_resolution_y_px = 2\n"
                                        << "focal_length_mm = 50\nsensor_size_mm = 36\n[extrinsics]\n"
                                        << "num_cams_x = 1\nnum_cams_y = 1\nbaseline_mm = 10\n";
  EXPECT_NE(errorOf(hci).find("parameters.cfg: missing extrinsics.focus_distance_m"), std::string::npos)
      << errorOf(hci);
  std::ofstream(hci / "parameters.cfg", std::ios::app) << "focus_distance_m = 2\n";
  EXPECT_NE(errorOf(hci).find("no depth maps"), std::string::npos) << errorOf(hci);
  // A colour image to go with it, then depths that are wrong in size or value.
  fs::copy_file(set / "view_0000.png", hci / "input_Cam000.png");
  DepthImage depth(4, 2);
  writePfm(depth, hci / "gt_depth_lowres_Cam000.pfm");
  EXPECT_NE(errorOf(hci).find("depth is 4x2"), std::string::npos) << errorOf(hci);
  DepthImage nan(48, 36);
  nan.at(3, 1) = std::nanf("");
  writePfm(nan, hci / "gt_depth_lowres_Cam000.pfm");
  EXPECT_NE(errorOf(hci).find("at pixel (3, 1) is not a finite distance"), std::string::npos) << errorOf(hci);
  std::ofstream(hci / "parameters.cfg", std::ios::app) << "[broken\n";
  EXPECT_NE(errorOf(hci).find("unterminated section"), std::string::npos) << errorOf(hci);
  EXPECT_NE(errorOf(freshDir("empty")).find("neither an mvr set"), std::string::npos);
}

}  // namespace
}  // namespace mvr
