#pragma once
// A folder of RGB-D references with their cameras, as mvr synthesize reads
// it. Two layouts:
//   mvr  a set `mvr render --depth` wrote: manifest.json (its cameras and
//        depth block), view_* colour and depth_* exr files.
//   hci  the 4D light-field benchmark's (Honauer et al. 2016):
//        parameters.cfg, input_Cam%03d.png, and depth as PFM: per camera
//        gt_depth_lowres_Cam%03d.pfm, or the centre camera's
//        gt_depth_lowres.pfm alone. Its cameras are a regular grid in one
//        plane with parallel axes and shifted sensors, which is a
//        shearing camera: image plane at focus_distance_m, camera (row r,
//        column c) of an nx x ny grid at x = (c - (nx - 1) / 2) baseline,
//        y = ((ny - 1) / 2 - r) baseline, pixel focal length
//        focal_length_mm / sensor_size_mm times the larger image side;
//        depth in metres along the optical axis. Camera 0 is the top left.
// Errors name the file and the problem: a missing file or field, a size
// mismatch, a depth that is not finite or negative.
#include <string>
#include <vector>

#include "mvr/camera.h"
#include "mvr/rgbd_view.h"

namespace mvr {

struct RgbdSet {
  std::string layout;  // "mvr" or "hci"
  int width = 0, height = 0;
  int views = 1, rows = 1;  // the grid the set was captured as
  CameraSpec camera;        // its track: the default for synthesis
  std::vector<RgbdView> references;
};

RgbdSet loadRgbdSet(const std::string& dir);

// Colour as RgbdView holds it: F32, linear (sRGB files decoded).
Image linearColor(const Image& image);

}  // namespace mvr
