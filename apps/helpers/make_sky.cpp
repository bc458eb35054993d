// Writes the procedural sky (apps/scenes/sky.h) as a cube strip and a sphere map
// pair of the same radiance.
//   make_sky --face 64 --cube sky_cube.png --spheres sky_spheres.png
#include <cstdio>
#include <string>

#include "apps/cli/cli.h"
#include "apps/scenes/sky.h"
#include "mvr/error.h"
#include "mvr/images/image_file.h"

int main(int argc, char** argv) {
  try {
    CLI::App app("Writes the procedural sky as a cube strip and a sphere map pair of the same "
                 "radiance.",
                 "make_sky");
    int face = 64;
    std::string cube, spheres;
    app.add_option("--face", face, "cube face size in pixels")
        ->check(CLI::Range(2, 4096))
        ->capture_default_str();
    app.add_option("--cube", cube, "the cube strip to write")->type_name("FILE.png")->required();
    app.add_option("--spheres", spheres, "the sphere map pair to write")->type_name("FILE.png")->required();
    if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
    mvr::writeImage(mvr::app::makeSkyCube(face), cube);
    // The pair's maps span the whole sphere in a disc: twice the face size
    // gives them about the cube's sampling rate.
    mvr::writeImage(mvr::app::makeSkySpherePair(2 * face), spheres);
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_sky: %s\n", e.what());
    return 1;
  }
}
