#include "mvr/camera.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mvr/error.h"

namespace mvr {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) fail("camera", what);
}

bool finite(double v) { return std::isfinite(v); }

}  // namespace

ShearingCamera::ShearingCamera(const CameraSpec& s, int width, int height, int views, int rows)
    : spec_(s), width_(width), height_(height), views_(views), rows_(rows) {
  const std::string side = "1.." + std::to_string(Limits::kMaxSide);
  require(width >= 1 && height >= 1 && width <= Limits::kMaxSide && height <= Limits::kMaxSide,
          "image size " + std::to_string(width) + "x" + std::to_string(height) + " outside " + side);
  require(views >= 1 && views <= Limits::kMaxViews,
          "view count must be 1.." + std::to_string(Limits::kMaxViews));
  require(rows >= 1 && rows <= Limits::kMaxRows,
          "row count must be 1.." + std::to_string(Limits::kMaxRows));
  for (double v : {s.distance, s.planeWidth, s.planeHeight, s.trackLeft, s.trackRight, s.rowTop,
                   s.rowBottom, s.nearDistance, s.farDistance})
    require(finite(v), "non-finite value");
  require(s.distance > 0, "distance must be positive");
  require(s.planeWidth > 0, "image plane width must be positive");
  require(s.planeHeight >= 0, "image plane height must not be negative");
  require(s.nearDistance > 0, "near distance must be positive");
  require(s.farDistance > s.nearDistance, "far distance must exceed near distance");
  require(s.trackRight >= s.trackLeft, "track right end lies left of its left end");
  planeWidth_ = s.planeWidth;
  planeHeight_ = s.planeHeight > 0 ? s.planeHeight : s.planeWidth * height / width;
  share_ = {{0, rows}, {0, height}, {0, views}};
}

ShearingCamera ShearingCamera::withShare(const RenderShare& share) const {
  auto within = [](IndexRange r, int n) { return r.begin >= 0 && r.begin <= r.end && r.end <= n; };
  require(within(share.rows, rows_) && within(share.scanlines, height_) && within(share.views, views_),
          "share outside the set");
  ShearingCamera part = *this;
  part.share_ = share;
  return part;
}

double ShearingCamera::viewX(int view) const {
  if (views_ == 1) return 0.5 * (spec_.trackLeft + spec_.trackRight);
  return spec_.trackLeft + view * (spec_.trackRight - spec_.trackLeft) / (views_ - 1);
}

glm::dvec3 ShearingCamera::eye(double view, int row) const {
  const double step = views_ > 1 ? (spec_.trackRight - spec_.trackLeft) / (views_ - 1) : 0.0;
  return {viewX(0) + view * step, rowY(row), spec_.distance};
}

double ShearingCamera::rowY(int row) const {
  if (rows_ == 1) return 0.5 * (spec_.rowTop + spec_.rowBottom);
  return spec_.rowTop + row * (spec_.rowBottom - spec_.rowTop) / (rows_ - 1);
}

double ShearingCamera::viewSpacing() const {
  return views_ == 1 ? 0.0 : (spec_.trackRight - spec_.trackLeft) / (views_ - 1);
}

glm::dmat4 ShearingCamera::viewProjection(int view, int row) const {
  return viewProjectionAt(viewX(view), rowY(row));
}

glm::dmat4 ShearingCamera::viewProjectionAt(double cx, double cy) const {
  const double D = spec_.distance, n = spec_.nearDistance, f = spec_.farDistance;
  const double sx = 2.0 / planeWidth_, sy = 2.0 / planeHeight_;
  glm::dmat4 m(0.0);  // column-major: m[column][row]
  // x_clip = sx (D X - cx Z)
  m[0][0] = sx * D;
  m[2][0] = -sx * cx;
  // y_clip = -sy (D Y - cy Z): negated so that window row 0 is the top.
  m[1][1] = -sy * D;
  m[2][1] = sy * cy;
  // Reversed zero-to-one depth: z_clip = n (f - d) / (f - n), d = D - Z.
  m[2][2] = n / (f - n);
  m[3][2] = n * (f - D) / (f - n);
  // w = d = D - Z
  m[2][3] = -1.0;
  m[3][3] = D;
  return m;
}

glm::dmat4 ShearingCamera::worldToCamera(int view, int row) const {
  const glm::dvec3 e = eye(view, row);
  return worldToCameraAt(e.x, e.y);
}

glm::dmat4 ShearingCamera::worldToCameraAt(double cx, double cy) const {
  glm::dmat4 v(1.0);  // column-major: v[column][row]
  v[1][1] = v[2][2] = -1.0;
  v[3] = glm::dvec4(0.0 - cx, cy, spec_.distance, 1.0);  // 0 - x: no negative zero in manifests
  return v;
}

glm::dmat3 ShearingCamera::intrinsics(int view, int row) const {
  const glm::dvec3 e = eye(view, row);
  return intrinsicsAt(e.x, e.y);
}

glm::dmat3 ShearingCamera::intrinsicsAt(double cx, double cy) const {
  glm::dmat3 k(0.0);
  k[0][0] = width_ * spec_.distance / planeWidth_;
  k[1][1] = height_ * spec_.distance / planeHeight_;
  k[2][0] = 0.5 * width_ + width_ / planeWidth_ * cx;
  k[2][1] = 0.5 * height_ - height_ / planeHeight_ * cy;
  k[2][2] = 1.0;
  return k;
}

glm::dvec3 ShearingCamera::project(const glm::dvec3& p, int view, int row) const {
  glm::dvec4 c = viewProjection(view, row) * glm::dvec4(p, 1.0);
  return {(c.x / c.w + 1.0) * 0.5 * width_, (c.y / c.w + 1.0) * 0.5 * height_, c.z / c.w};
}

glm::dvec3 ShearingCamera::unprojectAt(double cx, double cy, const glm::dvec3& window) const {
  // Inverse of viewProjectionAt: depth = n (f - w) / ((f - n) w), w = D - Z.
  const double n = spec_.nearDistance, f = spec_.farDistance, D = spec_.distance;
  const double w = n * f / (window.z * (f - n) + n), Z = D - w;
  const double xNdc = 2.0 * window.x / width_ - 1.0, yNdc = 2.0 * window.y / height_ - 1.0;
  const double X = (xNdc * w * planeWidth_ / 2.0 + cx * Z) / D;
  const double Y = (-yNdc * w * planeHeight_ / 2.0 + cy * Z) / D;
  return {X, Y, Z};
}

double ShearingCamera::disparityPerUnitTrack(double z) const {
  return -(width_ / planeWidth_) * z / (spec_.distance - z);
}

CameraSpec ShearingCamera::frame(const Bounds& b, int width, int height) {
  const glm::dvec3 lo(b.min), hi(b.max);
  const glm::dvec3 extent = glm::max(glm::abs(lo), glm::abs(hi));
  double radius = glm::length(extent);
  if (!(radius > 0)) radius = 1.0;
  const double aspect = double(width) / height;
  CameraSpec s;
  s.distance = 4.0 * radius;
  s.trackLeft = -0.25 * s.distance;
  s.trackRight = 0.25 * s.distance;
  // Size the plane so every corner of the bounds, seen from either end of
  // the track, lands inside the image: X' = cx + (X - cx) D / (D - Z).
  double halfX = 0, halfY = 0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
    const double scale = s.distance / (s.distance - p.z);
    for (double cx : {s.trackLeft, s.trackRight})
      halfX = std::max(halfX, std::abs(cx + (p.x - cx) * scale));
    halfY = std::max(halfY, std::abs(p.y * scale));
  }
  const double halfWidth = 1.05 * std::max({halfX, halfY * aspect, 1e-6 * radius});
  s.planeWidth = 2.0 * halfWidth;
  s.planeHeight = s.planeWidth / aspect;
  // Rows of views for full parallax span the same angle vertically.
  s.rowTop = 0.25 * s.distance / aspect;
  s.rowBottom = -s.rowTop;
  s.nearDistance = s.distance - 1.5 * radius;
  s.farDistance = s.distance + 1.5 * radius;
  return s;
}

}  // namespace mvr
