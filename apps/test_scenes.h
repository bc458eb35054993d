#pragma once
// Scenes the benchmark builds in memory.
#include "mvr/camera.h"
#include "mvr/scene.h"

namespace mvr::app {

// Halle 7.6's bad case for MVR: `count` long, slender vertical quads that
// span the image height, spread over x and depth. Each costs SVR two
// triangles but MVR one slice per scanline.
Scene makeSlenderScene(int count);

// Halle's rule of thumb needs the average height in pixels of the
// triangles that reach the image, seen from the centre of the track.
double averagePolygonHeight(const Scene& scene, const ShearingCamera& camera);

}  // namespace mvr::app
