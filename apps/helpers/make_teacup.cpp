// Writes the procedural teacup (apps/scenes/teacup.h), or the knot the bench
// measures unseen geometry on (apps/scenes/test_scenes.h), as PLY at about the
// requested triangle count.
//   make_teacup --triangles 4000 --out teacup.ply
//   make_teacup --shape knot --triangles 40000 --out knot.ply
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/cli/cli.h"
#include "apps/scenes/teacup.h"
#include "apps/scenes/test_scenes.h"
#include "mvr/error.h"
#include "mvr/assets/mesh_io.h"

int main(int argc, char** argv) {
  try {
    CLI::App app("Writes the procedural teacup (or knot) as PLY at about N triangles.", "make_teacup");
    int triangles = 4000;
    std::string out, shape = "teacup";
    app.add_option("--triangles", triangles, "about this many triangles")
        ->check(CLI::Range(100, 10000000))
        ->capture_default_str();
    app.add_option("--shape", shape, "teacup, or knot: a trefoil knot tube (mvr bench --knot)")
        ->check(CLI::IsMember({"teacup", "knot"}))
        ->capture_default_str();
    app.add_option("--out", out, "the PLY file to write")->type_name("FILE.ply")->required();
    if (auto exit = mvr::app::parseCommandLine(app, argc, argv)) return *exit;
    mvr::Scene cup = shape == "knot" ? mvr::app::makeKnotScene(triangles) : mvr::app::makeTeacup(triangles);
    mvr::saveMeshPly(cup, out);
    std::fprintf(stderr, "make_teacup: %zu triangles, %zu vertices -> %s\n", cup.triangleCount(),
                 cup.vertexCount(), out.c_str());
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_teacup: %s\n", e.what());
    return 1;
  }
}
