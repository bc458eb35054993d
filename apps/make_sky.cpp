// Writes the procedural sky (apps/sky.h) as a cube strip and a sphere map
// pair of the same radiance.
//   make_sky --face 64 --cube sky_cube.png --spheres sky_spheres.png
#include <cstdio>
#include <string>

#include "apps/args.h"
#include "apps/sky.h"
#include "mvr/error.h"
#include "mvr/io/image_file.h"

int main(int argc, char** argv) {
  try {
    if (argc > 1 && std::string(argv[1]) == "--help") {
      std::puts("usage: make_sky [--face N] --cube FILE.png --spheres FILE.png");
      return 0;
    }
    mvr::app::Args args(argc, argv, 1, {"face", "cube", "spheres"}, {});
    const int face = args.getInt("face", 64, 2, 4096);
    if (!args.has("cube") || !args.has("spheres")) mvr::fail("make_sky", "needs --cube and --spheres");
    mvr::writeImage(mvr::app::makeSkyCube(face), args.get("cube", ""));
    // The pair's maps span the whole sphere in a disc: twice the face size
    // gives them about the cube's sampling rate.
    mvr::writeImage(mvr::app::makeSkySpherePair(2 * face), args.get("spheres", ""));
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_sky: %s\n", e.what());
    return 1;
  }
}
