#pragma once
// Depth-image warping (mvr/backends/warp/depth_warp.h) on the CPU, EPI by EPI. On a
// shearing track a reference's pixel keeps its row and its camera z in
// every view of the track's row and moves along the row linearly in the
// camera's x, by (W / Wp) (1 - D / z) pixels per unit: so scanline j of
// every view is warped from scanline j of the references alone, and the
// grid's cells that cross it are segments between neighbouring pixel
// centres whose ends move linearly with the view, Halle's polygon slice
// tracks in one dimension. Each view's row is filled from its two
// nearest references (the GL back end's pair), each into its own line
// with a depth test, and the two lines composited with the same weight
// (warpWeight). Exact where the GL warp approximates: no merged cells,
// every segment its own.
//
// What differs from the GL warp, by design: a segment is drawn wherever
// both its pixels have samples and sheeted where those two differ by more
// than tau (the GL grid drops a cell that touches an empty pixel above or
// below, and sheets a cell by its three corners); the composite's angles
// come from atan2 of the point's distance from the track (the eyes lie on
// one line) and it and the weight's cosine from polynomials within 1e-5
// and 4e-6 (the GL composite: acos of 3D vectors and cos, in float);
// and where a source measured its silhouette inside a pixel
// (RgbdView::ends), the segment ends there, not at the pixel's centre
// with a pixel-wide footprint: the grid's outline stair-steps by a pixel
// at every silhouette, which cost warp its last 2-4 dB on unseen meshes
// (bunny 320x240 x 100, min over views: 29.9 -> 33.4 dB).
#include <memory>
#include <vector>

#include "mvr/camera.h"
#include "mvr/image.h"
#include "mvr/rgbd_view.h"

namespace mvr {

class WarpSpans {
 public:
  // One row of views of cam; tau and a as DepthWarp's. cam must outlive this.
  WarpSpans(const ShearingCamera& cam, int row, PixelType type, float tau, float a);

  // A reference on the row's track: colour (F32, linear) and camera z of
  // the camera's size, rendered at camera x on the row. Returns its index.
  int add(std::shared_ptr<const RgbdView> view, double x);
  int add(RgbdView view, double x) { return add(std::make_shared<const RgbdView>(std::move(view)), x); }

  // The EPI of scanline j: every view of the row, W x N pixels of epi's
  // type, row i = view i; alpha 0 where neither reference covers.
  void fillEpi(int scanline, const PixelRows& epi) const;
  // Pixels of view `view` that references a or b cover but only with
  // labelled (occluded) samples: the hierarchical acquisition's test
  // (DepthWarp::holes). Runs on the pool.
  long holes(int a, int b, int view) const;

  // The two references a view is composited from (nearestPair,
  // mvr/backends/warp/depth_warp.h).
  std::pair<int, int> pairOf(int view) const;

 private:
  struct Row;   // one reference's scanline, ready to warp
  struct Line;  // one reference warped into one view's scanline
  Row rowOf(int ref, int scanline) const;
  void warp(const Row& row, double refX, const Row* other, double otherX, double eyeX, Line& out) const;
  bool seenThrough(const Row& other, float x, float inv, float invFar, float toOther) const;
  void composite(const Line& l0, const Line* l1, int scanline, int view, int a, int b, uint8_t* out) const;

  const ShearingCamera& cam_;
  int row_;
  struct Reference {
    std::shared_ptr<const RgbdView> view;
    double x = 0.0;
    std::vector<float> labels;
    std::vector<uint8_t> silhouette;  // per pixel: 1 where labelPixels found one
  };
  std::vector<Reference> refs_;
  std::vector<glm::dvec3> centres_;  // (x, 0, 0) of each reference, for nearestPair
  PixelType type_;
  float tau_, a_;
  double perUnit_, focal_;  // pixels per unit of camera x at infinite depth: W / Wp; W D / Wp
};

}  // namespace mvr
