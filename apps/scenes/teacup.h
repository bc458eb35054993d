#pragma once
// Halle's test object, procedurally: a thick-walled cup of revolution with a
// tube handle and coloured patches, at about `triangles` triangles (85% in
// the body, 15% in the handle), centred near the origin, about 2 units wide.
#include "mvr/scene.h"

namespace mvr::app {

Scene makeTeacup(int triangles);

}  // namespace mvr::app
