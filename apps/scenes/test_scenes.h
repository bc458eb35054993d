#pragma once
// Scenes the benchmark builds in memory.
#include "mvr/camera.h"
#include "mvr/scene.h"

namespace mvr::app {

// Halle 7.6's bad case for MVR: `count` long, slender vertical quads that
// span the image height, spread over x and depth. Each costs SVR two
// triangles but MVR one slice per scanline.
Scene makeSlenderScene(int count);

// What image-based back ends find hard (issue 18): `bars` thin vertical
// bars, about a pixel wide at 160 pixels across, at several depths in
// front of a deep open box whose inner walls (coloured by depth) the bars
// and the box's rim hide and reveal as the view moves.
Scene makeThinAndDeepScene(int bars = 12);

// A mesh no back end was tuned on: a trefoil knot tube about 2 units wide
// at about `triangles` triangles, lit, coloured along its length; it
// hides and shows itself where it crosses over as the view moves.
Scene makeKnotScene(int triangles);

// Halle's rule of thumb needs the average height in pixels of the
// triangles that reach the image, seen from the centre of the track.
double averagePolygonHeight(const Scene& scene, const ShearingCamera& camera);

}  // namespace mvr::app
