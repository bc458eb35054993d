#include <gtest/gtest.h>

#include "mvr/camera.h"
#include "mvr/error.h"
#include "mvr/scene.h"

namespace mvr {
namespace {

CameraSpec spec() {
  CameraSpec s;
  s.distance = 4.0;
  s.planeWidth = 2.0;
  s.trackLeft = -1.0;
  s.trackRight = 1.0;
  s.nearDistance = 1.0;
  s.farDistance = 8.0;
  return s;
}

TEST(ShearingCamera, PointOnImagePlaneHasSamePixelInEveryView) {
  ShearingCamera cam(spec(), 200, 100, 9);
  const glm::dvec3 p(0.3, -0.2, 0.0);
  const glm::dvec3 first = cam.project(p, 0);
  for (int i = 1; i < cam.views(); ++i) {
    glm::dvec3 q = cam.project(p, i);
    EXPECT_NEAR(q.x, first.x, 1e-9) << "view " << i;
    EXPECT_NEAR(q.y, first.y, 1e-9) << "view " << i;
  }
  // Plane 2 x 1: x = (0.3 + 1) / 2 * 200 = 130; y down: (1 + 0.2 / 0.5) / 2 * 100 = 70.
  EXPECT_NEAR(first.x, 130.0, 1e-9);
  EXPECT_NEAR(first.y, 70.0, 1e-9);
}

TEST(ShearingCamera, PointAtDepthMovesLinearlyWithClosedFormDisparity) {
  ShearingCamera cam(spec(), 200, 100, 5);
  const double z = -2.0;  // behind the image plane
  const glm::dvec3 p(0.1, 0.4, z);
  // Disparity per view: -(W/Wp) z / (D - z) * spacing = -(100)(-2)/6 * 0.5.
  const double expected = 100.0 * 2.0 / 6.0 * 0.5;
  EXPECT_NEAR(cam.disparityPerUnitTrack(z) * cam.viewSpacing(), expected, 1e-12);
  for (int i = 0; i + 1 < cam.views(); ++i) {
    const double dx = cam.project(p, i + 1).x - cam.project(p, i).x;
    EXPECT_NEAR(dx, expected, 1e-9) << "view " << i;
    EXPECT_NEAR(cam.project(p, i + 1).y, cam.project(p, i).y, 1e-12);
  }
}

TEST(ShearingCamera, DepthIsReversedAndViewIndependent) {
  ShearingCamera cam(spec(), 64, 64, 3);
  // Camera plane z = 4; near plane at z = 3, far plane at z = -4.
  EXPECT_NEAR(cam.project({0, 0, 3.0}, 1).z, 1.0, 1e-12);
  EXPECT_NEAR(cam.project({0, 0, -4.0}, 1).z, 0.0, 1e-12);
  EXPECT_NEAR(cam.project({0.5, 0.1, -1.0}, 0).z, cam.project({0.5, 0.1, -1.0}, 2).z, 1e-12);
}

TEST(ShearingCamera, OneViewSitsAtTrackCentre) {
  ShearingCamera cam(spec(), 10, 10, 1);
  EXPECT_EQ(cam.viewX(0), 0.0);
  EXPECT_EQ(cam.viewSpacing(), 0.0);
}

// K V p, divided by its z, lands where project() puts p, in every view of
// a full-parallax grid; camera z is the distance from the camera plane.
// By hand for the centre view of spec() at 200x100 (plane 2 x 1, D = 4):
// fx = 200 * 4 / 2 = 400, fy = 100 * 4 / 1 = 400, principal point at the
// image centre; the point (0.5, 0.25, 1) is 3 in front of the eye, at
// u = 100 + 400 * 0.5 / 3, v = 50 - 400 * 0.25 / 3.
TEST(ShearingCamera, PinholeCamerasReproduceProjection) {
  CameraSpec s = spec();
  s.rowTop = 0.6, s.rowBottom = -0.6;
  const ShearingCamera one(spec(), 200, 100, 3);
  const glm::dvec3 p(0.5, 0.25, 1.0);
  const glm::dvec3 c = glm::dvec3(one.worldToCamera(1) * glm::dvec4(p, 1.0));
  EXPECT_DOUBLE_EQ(c.z, 3.0);
  const glm::dvec3 uv = one.intrinsics(1) * c / c.z;
  EXPECT_NEAR(uv.x, 100.0 + 400.0 * 0.5 / 3.0, 1e-9);
  EXPECT_NEAR(uv.y, 50.0 - 400.0 * 0.25 / 3.0, 1e-9);

  const ShearingCamera cam(s, 64, 48, 5, 3);
  for (int row = 0; row < 3; ++row)
    for (int view = 0; view < 5; ++view)
      for (const glm::dvec3 q : {glm::dvec3(0.3, -0.2, 1.5), glm::dvec3(-0.7, 0.4, -2.0), glm::dvec3(0.1, 0.2, 0.0)}) {
        const glm::dvec3 e = cam.eye(view, row);
        const glm::dvec3 inCamera = glm::dvec3(cam.worldToCamera(view, row) * glm::dvec4(q, 1.0));
        EXPECT_NEAR(inCamera.z, e.z - q.z, 1e-12);
        EXPECT_NEAR(inCamera.x, q.x - e.x, 1e-12);  // x right, y down
        EXPECT_NEAR(inCamera.y, e.y - q.y, 1e-12);
        const glm::dvec3 pixel = cam.intrinsics(view, row) * inCamera / inCamera.z;
        const glm::dvec3 expected = cam.project(q, view, row);
        EXPECT_NEAR(pixel.x, expected.x, 1e-9) << view << " " << row;
        EXPECT_NEAR(pixel.y, expected.y, 1e-9) << view << " " << row;
      }
}

TEST(ShearingCamera, ImpossibleCamerasAreRejected) {
  auto bad = [](auto change) {
    CameraSpec s = spec();
    change(s);
    return s;
  };
  EXPECT_THROW(ShearingCamera(bad([](CameraSpec& s) { s.distance = 0; }), 8, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(bad([](CameraSpec& s) { s.farDistance = 0.5; }), 8, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(bad([](CameraSpec& s) { s.nearDistance = -1; }), 8, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(bad([](CameraSpec& s) { s.trackRight = -2; }), 8, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(bad([](CameraSpec& s) { s.planeWidth = NAN; }), 8, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(spec(), 0, 8, 2), Error);
  EXPECT_THROW(ShearingCamera(spec(), 8, 8, 0), Error);
}

TEST(ShearingCamera, FrameKeepsBoundsInsideTheImageAndClipRange) {
  Bounds b{glm::vec3(-1, -0.5, -0.8), glm::vec3(1, 0.5, 0.8)};
  CameraSpec s = ShearingCamera::frame(b, 320, 240);
  ShearingCamera cam(s, 320, 240, 2);
  for (int view : {0, 1})
    for (int corner = 0; corner < 8; ++corner) {
      glm::dvec3 p(corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y,
                   corner & 4 ? b.max.z : b.min.z);
      glm::dvec3 q = cam.project(p, view);
      EXPECT_GT(q.x, 0);
      EXPECT_LT(q.x, 320);
      EXPECT_GT(q.y, 0);
      EXPECT_LT(q.y, 240);
      EXPECT_GT(q.z, 0);
      EXPECT_LT(q.z, 1);
    }
}

}  // namespace
}  // namespace mvr
