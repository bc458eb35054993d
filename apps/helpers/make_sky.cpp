// Writes the procedural sky (apps/scenes/sky.h) as a cube strip and a sphere map
// pair of the same radiance (reflection maps), or as an equirectangular
// HDR environment.
//   make_sky --face 64 --cube sky_cube.png --spheres sky_spheres.png
//   make_sky --equirect sky.exr --width 512 --sun 40
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
    int face = 64, width = 512;
    float sun = 1.0f;
    std::string cube, spheres, equirect;
    app.add_option("--face", face, "cube face size in pixels")
        ->check(CLI::Range(2, 4096))
        ->capture_default_str();
    app.add_option("--cube", cube, "the cube strip to write")->type_name("FILE.png");
    app.add_option("--spheres", spheres, "the sphere map pair to write")->type_name("FILE.png");
    app.add_option("--equirect", equirect, "the equirectangular environment to write")->type_name("FILE.exr");
    app.add_option("--width", width, "the environment's width (its height is half)")
        ->check(CLI::Range(2, 16384))
        ->capture_default_str();
    app.add_option("--sun", sun, "the environment's sun radiance, times the sky's")
        ->check(CLI::Range(0.0f, 1e6f))
        ->capture_default_str();
    if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
    if (cube.empty() && spheres.empty() && equirect.empty()) throw mvr::Error("nothing to write: give --cube, --spheres or --equirect");
    if (!cube.empty()) mvr::writeImage(mvr::app::makeSkyCube(face), cube);
    // The pair's maps span the whole sphere in a disc: twice the face size
    // gives them about the cube's sampling rate.
    if (!spheres.empty()) mvr::writeImage(mvr::app::makeSkySpherePair(2 * face), spheres);
    if (!equirect.empty()) {
      mvr::ImageEncoding half;
      half.bits = 16, half.srgb = false;
      mvr::writeImage(mvr::app::makeSkyEquirect(width, sun), equirect, half);
    }
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_sky: %s\n", e.what());
    return 1;
  }
}
