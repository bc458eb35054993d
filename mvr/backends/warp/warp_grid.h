#pragma once
// A reference's grid mesh for the GL warp (mvr/backends/warp/depth_warp.h): which
// of the grid's triangles are drawn, merged into quads where they lie on a
// plane, and the silhouette pixels' own footprints (splats).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/rgbd_view.h"

namespace mvr {

// The grid (DepthWarp::ensureGrid): (W + 2) x (H + 2) vertices, vertex
// (i, j) at pixel centre (i - 1/2, j - 1/2) clamped to the image, fetching
// the pixel it lies in.
int gridPixel(int k, int n);

// The triangles; those across a depth jump (rubber sheets) last, from
// index `sheets` on, each with its farthest vertex last (the provoking
// vertex: kWarpVertex's vFar).
struct GridLists {
  std::vector<uint32_t> indices;
  size_t sheets = 0;
};

// The grid's triangles that touch only pixels with samples: a triangle
// with a vertex on an empty pixel would draw nothing, so it is left out of
// the reference's list rather than transformed for every view; most of a
// scene's image is background. And where a rectangle of cells lies on a
// plane (no occlusion label, 1/z affine over all of its vertices within
// `deviation`: a plane's 1/z is affine in its image), the rectangle is one
// quad: its inner vertices land within that of the quad's plane. A vertex
// at camera z moves f e / z pixels in a view e from the reference (focal
// length f in pixels), so a deviation of 1/z moves it f e times that.
// Triangles are what a CPU rasterizer pays for per view.
GridLists gridTriangles(const DepthImage& depth, const std::vector<float>& labels, float tau, float deviation);

// A silhouette pixel's footprint as a quad (kWarpVertex): four corners,
// each (corner, pixel centre), and two triangles. One indexed draw for
// all: a CPU GL runs every instance of an instanced draw as its own draw.
struct Splats {
  std::vector<glm::vec4> vertices;
  std::vector<uint32_t> indices;
};

Splats makeSplats(const std::vector<uint32_t>& pixels, int width);

}  // namespace mvr
