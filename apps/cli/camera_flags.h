#pragma once
// The camera in a display user's terms, on the command line (issue 19):
// the view cone, the field of view, the scene depth that sits on the
// display plane, a disparity scale, and a background. They adjust the
// camera the scene file gives (or the one framed around a bare mesh):
//   --cone DEG        the track spans DEG degrees seen from the centre of
//                     the image plane: ends at -+ D tan(DEG / 2)
//   --fov DEG         the centre view's horizontal field of view: image
//                     plane 2 D tan(DEG / 2) wide (height by aspect)
//   --focal Z|center  world z that sits on the display (image) plane: the
//                     camera rig moves along z with it (implemented by
//                     moving the scene by -Z; manifests keep the scene's
//                     own world coordinates)
//   --depthiness S    disparity times S: the track (and rows) scaled by S
//   --camera NAME|INDEX  the scene file's own camera (glTF) as the centre
//                     view (mvr/file_camera.h); the options above adjust it
//   --background RGBA and --opaque: composited in linear light
//                     (BackgroundSink)
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "mvr/camera.h"
#include "mvr/scene.h"

namespace mvr::app {

struct CameraFlags {
  std::optional<double> cone, fov, depthiness;
  std::string focal, background, fileCamera;
  bool opaque = false;

  void add(CLI::App& app);
  // Throws mvr::Error naming the option for a value out of range.
  void validate() const;
  // The first of these options the command line gave ("--cone"), or "".
  std::string firstGiven() const;
  // With --camera: moves the scene into that camera's view and makes it
  // the scene's camera; returns the move (identity without --camera).
  glm::mat4 viewThroughFileCamera(Scene& scene, int width, int height) const;
  // Moves the scene (Scene::transform) so that the focal depth lies on
  // z = 0, the centre of `framed` (a sequence's every pose) or of the
  // scene's bounds; returns how far the rig moved along z (0 without --focal).
  double placeFocalPlane(Scene& scene, const Bounds* framed = nullptr) const;
  CameraSpec adjust(CameraSpec spec, int width, int height) const;
  // The background to composite over, if any.
  std::optional<glm::vec4> backgroundColor() const;
};

}  // namespace mvr::app
