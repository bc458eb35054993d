#pragma once
// Scene files (JSON) and bare meshes. Format: docs/SCENE_FORMAT.md.
#include <string>

#include "mvr/scene.h"

namespace mvr {

// A .json path is a scene file; anything else is a bare mesh, centred on the
// origin and given a default light (the camera is framed by the caller).
// Errors are one line: "<file>: <json path>: <problem>". Faces a mesh file
// holds but cannot be used (a repeated corner, a vertex index out of range)
// are dropped and counted in Scene::droppedFaces; strict makes them an
// error.
Scene loadScene(const std::string& path, bool strict = false);

// "<file>: N faces dropped (...)" when the scene dropped any, else empty:
// the warning every command prints.
std::string droppedFacesWarning(const Scene& scene);

// The scene bundled with the program (assets/default.json).
std::string defaultScenePath();

// A scene's camera, or one framed on its bounds.
CameraSpec cameraFor(const Scene& scene, int width, int height);

}  // namespace mvr
