#pragma once
// FBX, Collada and 3DS files, read by assimp in a child process: the
// mvr-import program beside this one (or MVR_IMPORT), which limits its own
// memory and CPU time and writes the model back through a pipe
// (imported_model.h). assimp's readers are not safe on every input; in a
// child, a crash or a hang is one line here, and this process is intact.
#include <string>

#include "mvr/scene.h"

namespace mvr {

bool isAssimpPath(const std::string& path);

// The model with assimp's hierarchy flattened into world coordinates and
// its polygons triangulated; normals where the file has none, smooth.
// Materials: the diffuse (or PBR base) colour and texture (a file relative
// to the model, found as findFile tolerates, or an image the file
// embeds), the specular colour times its strength, the shininess. Throws
// mvr::Error naming the file: assimp's own message, a crash, or more than
// 300 s.
Scene importWithAssimp(const std::string& path);

}  // namespace mvr
