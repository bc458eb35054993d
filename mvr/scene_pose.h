#pragma once
// A scene at a moment of a sequence (issue 47): its geometry posed from the
// still scene it was loaded as, in place, so that a renderer holding the
// scene sees it move (Renderer::sceneMoved). Lights and the files' cameras
// stay where they are in the world: a turntable turns the model under the
// studio's lights, before a camera that does not move.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/scene.h"

namespace mvr {

// Turns by `degrees` about the vertical (+y) axis through `pivot`,
// right-handed: a positive angle turns +x toward -z.
glm::mat4 turntable(const glm::vec3& pivot, double degrees);

// scene's positions and normals become still's moved by m. The two have
// the same vertices (scene began as a copy of still).
void poseGeometry(Scene& scene, const Scene& still, const glm::mat4& m);

// Every animation of the scene (one per animated file) at time t, moved
// last by `after`. clip: the name of the one clip that plays ("": all);
// a file without it stays at rest.
void poseAnimations(Scene& scene, double t, const std::string& clip, const glm::mat4& after);
// The longest of the scene's clips, or of those named `clip`; 0: none.
double animationLength(const Scene& scene, const std::string& clip);
bool hasClip(const Scene& scene, const std::string& clip);
// The times whose poses a camera is framed on so that every pose of the
// clips that play stays in the picture: each key time of every channel,
// and the midpoint between neighbouring keys (where a slerp's arc or a
// cubic's overshoot leaves the keys' poses most), ascending. Where there
// are more than `most` (2 or more), `most` spread evenly over the list,
// its first and last kept. None for a scene without animation.
std::vector<double> framingTimes(const Scene& scene, const std::string& clip, size_t most);

}  // namespace mvr
