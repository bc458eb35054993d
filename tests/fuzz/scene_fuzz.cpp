// libFuzzer target: the scene loader (issue 16). The first byte picks the
// file's kind (JSON scene, PLY, OBJ, STL, OFF, glTF, GLB, Collada, FBX,
// 3DS), the rest is its content.
// A rejection (mvr::Error) is the expected answer to bad input; anything
// else (a crash, a sanitizer report, another exception, a hang) is a
// defect. Scene files may name "m.obj", a valid mesh beside them. An OBJ
// input is also written as "lib.mtl", so that one input is both the OBJ
// and the MTL its "mtllib lib.mtl" reads (each reader skips the other's
// statements).
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "mvr/error.h"
#include "mvr/assets/scene_io.h"
#include "mvr/scene_pose.h"

namespace {

std::filesystem::path dir;

void removeDir() {
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char pattern[] = "/tmp/mvr_scene_fuzz_XXXXXX";
  if (!mkdtemp(pattern)) std::abort();
  dir = pattern;
  std::atexit(removeDir);
  // An importer (assimp, in its child process) that hangs is killed well
  // within libFuzzer's 10 s an input, twice for a Collada file read again:
  // the hang is assimp's, surviving it is ours.
  setenv("MVR_IMPORT_SECONDS", "3", 1);
  std::ofstream(dir / "m.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kExtensions[] = {".json", ".ply", ".obj", ".stl", ".off"};
  if (size == 0) return 0;
  // A first byte from 250 picks glTF (.gltf to 252, .glb above), 244 to
  // 249 assimp's formats (read by mvr-import in a child process); below,
  // the kinds as the saved crashers and seeds were written.
  static const char* const kAssimp[] = {".dae", ".fbx", ".3ds"};
  const char* ext = data[0] >= 253   ? ".glb"
                    : data[0] >= 250 ? ".gltf"
                    : data[0] >= 244 ? kAssimp[(data[0] - 244) % 3]
                                     : kExtensions[data[0] % 5];
  const std::filesystem::path path = dir / (std::string("input") + ext);
  const std::filesystem::path mtl = dir / "lib.mtl";
  for (const std::filesystem::path& file : {path, mtl}) {
    if (file == mtl && std::string(ext) != ".obj") continue;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  }
  try {
    mvr::Scene scene = mvr::loadScene(path.string(), size % 2 == 0);
    // An animated file is posed too (before its keys, between, after).
    for (double t : {-1.0, 0.37, 1e9}) mvr::poseAnimations(scene, t, "", glm::mat4(1.0f));
  } catch (const mvr::Error&) {
  }
  std::error_code ec;
  std::filesystem::remove(path, ec);
  std::filesystem::remove(mtl, ec);
  return 0;
}
