#pragma once
// A procedural sky for reflection maps: a graded sky with a sun, a hue band
// round the horizon (so that reflections show which way they point) and a
// checkered ground. The same radiance function written out in both map
// kinds EnvironmentSet reads, so the two can be compared on one scene.
#include <glm/glm.hpp>

#include "mvr/image.h"

namespace mvr::app {

glm::vec3 skyRadiance(glm::vec3 direction);
// 6:1 strip of face x face squares, GL cube map convention.
Image makeSkyCube(int face);
// 2:1: the sphere maps seen from +z (left) and from -z (right).
Image makeSkySpherePair(int size);
// 2:1 equirectangular, linear float (an environment, shading/image_light.h's
// axes), with the sun's radiance times sunScale (an HDR sky).
Image makeSkyEquirect(int width, float sunScale = 1.0f);

}  // namespace mvr::app
