#pragma once
// The regular-shearing camera (Halle 1997, ch. 3 and 5; docs/CONVENTIONS.md):
// image plane z = 0 holding a plane_width x plane_height rectangle centred
// on the origin; cameras on the plane z = distance looking along -z, view i
// at x = track_left + i (track_right - track_left) / (N - 1). Every view's
// frustum is sheared so the rectangle fills the image, so a point on the
// image plane has the same pixel position in every view.
//
// Pixel coordinates: x right, y down (row 0 is the top of the image), pixel
// (i, j) has its centre at (i + 0.5, j + 0.5). Clip space uses GL's
// zero-to-one depth with reversed Z (near -> 1, far -> 0) for precision.
#include <glm/glm.hpp>

#include "mvr/bounds.h"

namespace mvr {

// The one bounds table for a set's extent: the camera enforces it, and the
// command line's options and the stream's reader check against it.
struct Limits {
  static constexpr int kMaxViews = 65536;  // views per row
  static constexpr int kMaxRows = 4096;    // rows of views (full parallax)
  static constexpr int kMaxSide = 16384;   // image width and height, pixels
};

struct CameraSpec {
  double distance = 4.0;     // D: camera plane to image plane
  double planeWidth = 2.0;   // image-plane rectangle, world units
  double planeHeight = 0.0;  // 0: from the image aspect ratio
  double trackLeft = -1.0;   // camera x of view 0
  double trackRight = 1.0;   // camera x of view N - 1
  double rowTop = 0.0;       // camera y of row 0 (full parallax)
  double rowBottom = 0.0;    // camera y of row M - 1
  double nearDistance = 1.0; // clip distances from the camera plane
  double farDistance = 8.0;
};

// A half-open range of indices.
struct IndexRange {
  int begin = 0, end = 0;
  int size() const { return end - begin; }
  bool contains(int i) const { return i >= begin && i < end; }
};

// The part of a set one process renders when a job is split over
// processes (apps/mpi_render.h): the rows of views it renders and, of each
// row, the scanlines an EPI renderer fills and the views a view renderer
// draws. Every frame is computed exactly as in the whole render, so the
// parts join into the same bytes.
struct RenderShare {
  IndexRange rows, scanlines, views;
};

class ShearingCamera {
 public:
  // Throws mvr::Error for an impossible camera.
  ShearingCamera(const CameraSpec& spec, int width, int height, int views, int rows = 1);

  const CameraSpec& spec() const { return spec_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int views() const { return views_; }
  int rows() const { return rows_; }
  double planeWidth() const { return planeWidth_; }
  double planeHeight() const { return planeHeight_; }
  // The whole set unless restricted by withShare.
  const RenderShare& share() const { return share_; }
  // This camera rendering only part of its set; throws mvr::Error for a
  // share outside it.
  ShearingCamera withShare(const RenderShare& share) const;

  double viewX(int view) const;  // camera x of view i
  double rowY(int row) const;    // camera y of row r
  // The eye of view i in row r (on the camera plane, z = D); view may be
  // fractional: the eye moves linearly along the track.
  glm::dvec3 eye(double view, int row = 0) const;
  double viewSpacing() const;    // x distance between neighbouring views

  // World -> clip for one view. Only the x row depends on the view:
  // x_clip = (2/Wp)(D X - cx Z), w = D - Z.
  glm::dmat4 viewProjection(int view, int row = 0) const;
  glm::dmat4 viewProjectionAt(double cameraX, double cameraY) const;
  // World point -> (pixel x, pixel y, window depth) in one view.
  glm::dvec3 project(const glm::dvec3& p, int view, int row = 0) const;
  // Window (pixel x, pixel y, window depth) -> world point, for an eye at
  // (cameraX, cameraY) on the camera plane: the inverse of project.
  glm::dvec3 unprojectAt(double cameraX, double cameraY, const glm::dvec3& window) const;
  // One view as a pinhole camera in the convention RGB-D tools use
  // (OpenCV's axes): camera x right, y down, z along the view direction
  // (world -z), world units, so camera z of a point is its distance D - Z
  // from the camera plane. worldToCamera is V: the eye to the origin, then
  // diag(1, -1, -1). intrinsics is K, to this file's pixel coordinates
  // (centre of pixel (i, j) at (i + 0.5, j + 0.5)): u = fx x/z + cx with
  // fx = W D / Wp for every view; the frustum's shear is a principal point
  // that moves with the eye, cx = W/2 + (W/Wp) eye.x, cy = H/2 - (H/Hp) eye.y.
  glm::dmat4 worldToCamera(int view, int row = 0) const;
  glm::dmat3 intrinsics(int view, int row = 0) const;
  // The same for an eye anywhere on the camera plane (a source between views).
  glm::dmat4 worldToCameraAt(double cameraX, double cameraY) const;
  glm::dmat3 intrinsicsAt(double cameraX, double cameraY) const;
  // Pixel x movement of a point at depth z per unit of camera x:
  // -(W / Wp) z / (D - z). Zero on the image plane.
  double disparityPerUnitTrack(double z) const;

  // A camera that frames the given bounds, with the image-plane rectangle
  // at the origin, a track half as wide as the camera distance.
  static CameraSpec frame(const Bounds& bounds, int width, int height);

 private:
  CameraSpec spec_;
  int width_, height_, views_, rows_;
  double planeWidth_, planeHeight_;
  RenderShare share_;
};

}  // namespace mvr
