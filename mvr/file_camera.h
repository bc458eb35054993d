#pragma once
// A scene file's own camera as the rig's centre view (`--camera`; glTF's
// cameras, issue 46).
#include <string>

#include "mvr/camera.h"
#include "mvr/scene.h"

namespace mvr {

// The file camera `which` names (its name, else its index among
// scene.fileCameras) made the centre view of a width x height rig: the
// scene is moved into the camera's frame (its rotation and position; a
// scale in its node is dropped), then back along z by D, the distance of
// the scene's bounds centre along the camera's view, so that the image
// plane z = 0 passes through that centre. The plane's height is 2 D
// tan(yfov / 2), its width by the image's aspect; track and rows as a
// framed camera's (-+ D / 4; rows by aspect); near and far enclose the
// bounds. Throws mvr::Error naming "--camera" for no such camera, or a
// scene not in front of it. `moved`, where given, receives the move the
// scene was given (Scene::transform), for copies of the scene to follow.
CameraSpec viewThrough(Scene& scene, const std::string& which, int width, int height, glm::mat4* moved = nullptr);

}  // namespace mvr
