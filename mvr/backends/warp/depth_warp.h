#pragma once
// Novel views from two RGB-D references on the GPU (seed 003, chapter 5):
//   warp       one static grid of the references' W x H pixel centres
//              (X, Y only), drawn once per reference into its own target:
//              the vertex shader fetches the pixel's depth, unprojects it
//              with K and V, projects it into the virtual view and carries
//              the pixel's occlusion label (1 where a neighbour's depth
//              jumps by more than tau of the nearer depth, or it has no
//              sample: view independent, so labelled once per reference
//              instead of per vertex and view as the seed does); the
//              fragment shader writes colour, and the virtual camera's
//              depth signed by the label (rounded: a rubber sheet is
//              occluded over its half nearer the labelled vertices).
//              Triangles touching a pixel without a sample are dropped;
//              those across a jump (rubber sheets) are drawn and labelled,
//              except where the other reference sees through them: a
//              sheet's fragment stands for a surface on the view's ray
//              between the sheet and the jump's far side; if the other
//              reference, along that stretch's image in it, sees nothing
//              or surfaces beyond the stretch, nothing is there and the
//              fragment is dropped (not in the seed; on the scanned bunny
//              at 640x480 min PSNR 25.6 -> 31.6 dB).
//              A rectangle of up to 32 x 32 cells on one plane is one
//              quad, its colour fetched at uv = (uv z) / z, both linear in
//              the surface point: exact on the plane (143K teacup at
//              640x480: 14K triangles a reference, 20K with runs along
//              rows alone). No fragment but a sheet's is discarded, so a
//              CPU GL tests depth before shading.
//              A pixel beside one without a sample (a silhouette) is also
//              drawn as its own footprint, a flat square at its depth
//              (labelled), so silhouettes are not eroded by the half
//              pixel the grid of centres stops short of them.
//   composite  a full-screen pass over the pixels either reference drew
//              (their depth buffers tested) blends the two warped
//              references per pixel with the seed's weight (eqs. 5-1 to
//              5-3): the angular weight, the visibility test and the
//              occlusion penalty.
// The weight of reference i at a pixel whose surface point P the two
// warps agree on (the nearer one's), theta_i the angle at P between the
// rays to the virtual camera and to reference i, s = theta_i / (theta_i +
// theta_j):
//   wAng_i  = (1 + cos(pi s)) / 2: 1 at reference i, 1/2 halfway, 0 at j,
//             smooth at both ends (the seed's cosine form; its eq. 4-4 is
//             not in the excerpt we have, this is our reading of it);
//   closer  = 1 where i's depth is nearer than j's by more than tau of it;
//   phi_i   = min(1, occ_i (a s)^4) (eq. 5-2, saturated at 1: a = 30
//             makes the penalty total once s passes 1/30);
//   w_i     = min(1, phi_j + (1 - phi_i) clamp(wAng_i + phi_i closer_i
//             - phi_j closer_j, 0, 1)) (eq. 5-3), clamped to [0, 1];
//   colour  = w_i c_i + (1 - w_i) c_j. Where one reference has no sample,
//   the other alone; where neither, nothing (alpha 0).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "mvr/gl/gl_handles.h"
#include "mvr/gl/render_target.h"
#include "mvr/rgbd_view.h"

namespace mvr {

// The weight of reference 0 against reference 1 at a pixel both cover
// (above): theta the angles at the surface point, z their virtual depths,
// occ their occlusion labels. The composite pass computes the same in GLSL.
float warpWeight(float theta0, float theta1, float z0, float z1, float occ0, float occ1, float tau, float a);
// The same from s = theta0 / (theta0 + theta1) and cos(pi s), for the CPU
// warp (mvr/backends/warp/warp_spans.h), which computes both faster: F is float, or a
// vector of floats (GCC's vector extension) for several pixels at once,
// through the same operations in the same order, so each lane's weight is
// the scalar one bit for bit.
template <class F>
inline F compositeWeightOf(F s, F cosPiS, F z0, F z1, F occ0, F occ1, float tau, float a) {
  const F zero = F{}, one = zero + 1.0f;
  auto lesser = [](F x, F y) { return y < x ? y : x; };                   // std::min(x, y)
  auto unit = [&](F v) { return v < zero ? zero : one < v ? one : v; };  // std::clamp(v, 0, 1)
  const F wAng = 0.5f + 0.5f * cosPiS;
  const F closer0 = z0 - z1 < -tau * z0 ? one : zero;
  const F closer1 = z1 - z0 < -tau * z1 ? one : zero;
  const F p0 = a * s, p1 = a * (1.0f - s);
  const F phi0 = lesser(one, occ0 * (p0 * p0) * (p0 * p0));
  const F phi1 = lesser(one, occ1 * (p1 * p1) * (p1 * p1));
  return unit(lesser(one, phi1 + (1.0f - phi0) * unit(wAng + phi0 * closer0 - phi1 * closer1)));
}
inline float compositeWeight(float s, float cosPiS, float z0, float z1, float occ0, float occ1, float tau, float a) {
  return compositeWeightOf(s, cosPiS, z0, z1, occ0, occ1, tau, a);
}

// The two references a view is composited from, by their centres: the
// nearest, and the nearest of those beyond the eye from it (-1: none, or
// the eye is at the nearest). On a track, the pair that brackets the view.
std::pair<int, int> nearestPair(const std::vector<glm::dvec3>& centres, const glm::dvec3& eye);

// A reference resident on the GPU.
struct WarpReference {
  int width = 0, height = 0;
  gl::Texture color, depth, label;  // RGBA32F linear, R32F camera z, R32F occlusion label
  // Pixels with an empty 8-neighbour, each its own square (the splats).
  gl::Buffer splatVertices, splatIndices;
  size_t splatIndexCount = 0;
  // The grid's triangles whose three pixels have samples (the others draw
  // nothing), planar rectangles merged: the shared grid's vertices, this
  // reference's indices.
  gl::Buffer triangles;
  size_t triangleIndexCount = 0;
  size_t sheetIndexStart = 0;  // the triangles across a depth jump, from here on
  glm::mat4 pixelToWorld{1.0f};
  glm::vec3 center{0.0f};

  // The labels are view independent: made here once, with tau (DepthWarp).
  // A rectangle of grid cells becomes one quad where that moves none of
  // its vertices more than `flatness` pixels in a view `baseline` (world
  // units) from the reference's centre (0: none merged but exact planes).
  // Needs a current GL context.
  static WarpReference upload(const RgbdView& view, float tau, float flatness = 0.0f, double baseline = 0.0);
};

// The virtual camera of one view.
struct WarpCamera {
  glm::dmat4 viewProjection;  // world to clip, reversed Z (ShearingCamera); w = camera z
  glm::dmat4 pixelToWorld;    // RgbdView::pixelToWorld of its K and V
  glm::dvec3 center;
};

class DepthWarp {
 public:
  // tau: the relative depth difference that makes a discontinuity and a
  // nearer surface; a: the penalty's growth (eq. 5-2). Needs a current GL
  // context.
  DepthWarp(float tau, float a);

  // Composites references a and b (b may be null: a alone) into target,
  // whose size is the virtual view's.
  void render(const WarpReference& a, const WarpReference* b, const WarpCamera& view, const RenderTarget& target);
  // Pixels of a width x height view that a or b cover but only with
  // triangles labelled occluded (rubber sheets over what neither saw).
  long holes(const WarpReference& a, const WarpReference& b, const WarpCamera& view, int width, int height);

  // One reference warped alone into a width x height view: colour with
  // the occlusion label as alpha, and the virtual camera's z (0: not
  // covered).
  struct WarpedImage {
    Image color;  // F32
    DepthImage depth;
  };
  WarpedImage warped(const WarpReference& ref, const WarpCamera& view, int width, int height);

 private:
  // The warped reference: colour and signed virtual depth (kWarpFragment),
  // depth buffer.
  struct Warped {
    int width = 0, height = 0;
    gl::Texture color, zbuffer;
    gl::Framebuffer fbo;
  };
  void ensureGrid(int width, int height);  // the grid's vertices
  void ensureTargets(int width, int height);
  // clearColor: the colour target too, not just the depth buffer (render
  // reads colour only where the depth buffer says drawn).
  // other: the reference whose image tests ref's rubber sheets (null: none).
  void warp(const WarpReference& ref, const WarpReference* other, const WarpCamera& view, const Warped& into,
            bool clearColor) const;
  WarpedImage read(const Warped& from) const;

  gl::Program warp_, warpSheet_, composite_, compositeRest_;
  gl::VertexArray grid_, splats_, empty_;
  gl::Framebuffer over_;  // the target's colour alone (render)
  gl::Buffer gridVertices_;
  int gridWidth_ = 0, gridHeight_ = 0;
  Warped warped_[2];
};

// Whether two camera depths lie on one surface: apart by at most tau of
// the nearer (WarpOptions::tau). Both warps' labels, sheets and silhouette
// ends test with this.
inline bool oneSurface(float a, float b, float tau) { return std::abs(a - b) <= tau * std::min(a, b); }

// Per pixel its occlusion label: 1 where a 4-neighbour inside the image
// has no sample or a depth more than tau of the nearer away; and the
// silhouette pixels, samples with an empty 8-neighbour. Both warps label
// with this.
void labelPixels(const DepthImage& depth, float tau, std::vector<float>& labels, std::vector<uint32_t>& silhouettes);

}  // namespace mvr
