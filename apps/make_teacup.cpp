// Writes the procedural teacup (apps/teacup.h) as PLY at about the
// requested triangle count.
//   make_teacup --triangles 4000 --out teacup.ply
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "apps/args.h"
#include "apps/teacup.h"
#include "mvr/error.h"
#include "mvr/io/mesh_io.h"

int main(int argc, char** argv) {
  try {
    if (argc > 1 && std::string(argv[1]) == "--help") {
      std::puts("usage: make_teacup --triangles N --out FILE.ply");
      return 0;
    }
    mvr::app::Args args(argc, argv, 1, {"triangles", "out"}, {});
    const int triangles = args.getInt("triangles", 4000, 100, 10000000);
    if (!args.has("out")) mvr::fail("make_teacup", "needs --out FILE.ply");
    mvr::Scene cup = mvr::app::makeTeacup(triangles);
    mvr::saveMeshPly(cup, args.get("out", ""));
    std::fprintf(stderr, "make_teacup: %zu triangles, %zu vertices -> %s\n", cup.triangleCount(),
                 cup.vertexCount(), args.get("out", "").c_str());
    return 0;
  } catch (const mvr::Error& e) {
    std::fprintf(stderr, "make_teacup: %s\n", e.what());
    return 1;
  }
}
