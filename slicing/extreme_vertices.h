#pragma once
// Halle 5.6: every vertex is transformed once per sequence, to the two
// extreme views. In a regular-shearing camera only x depends on the view,
// and linearly, so each vertex keeps x at view 0 and its step per view; y,
// depth and 1/w are shared by all views. Attributes are stored divided by w
// for hyperbolic (perspective-correct) interpolation. Cost: O(vertices),
// independent of the view count.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/camera.h"
#include "mvr/scene.h"
#include "shading/lighting.h"
#include "shading/shading_plan.h"
#include "shading/texture_vector.h"

namespace mvr {

// A slice coloured by a 1-D texture vector of its own (Halle 6.5.3): the
// image-based back end's run of source pixels. The vector's parameter runs
// from u0 at the slice's end 0 to u1 at end 1, linearly in screen space.
struct SliceVector {
  int base = 0, length = 0;  // first texel and level-0 length in vectorTexels
  float u0 = 0.0f, u1 = 1.0f;
  // Split track (image slices of specular surfaces): knots
  // [firstKnot, firstKnot + knotCount) of ExtremeVertices::knots.
  int firstKnot = 0, knotCount = 0;
};

// A specular highlight added to a slice's colour, exact at EPI row
// coordinate r and linear in r between a slice's knots.
struct HighlightKnot {
  float r;
  glm::vec3 specular;
};

struct ExtremeVertices {
  // Per vertex, pixel units. x at EPI row coordinate r (view i is sampled
  // at r = i + 0.5) is x0 + (r - 0.5) * dx.
  std::vector<float> x0, dx, y, depth, invW;
  // Full parallax (Halle 5.6.11): between rows of views only y moves, by a
  // per-vertex step. y of row r is yFirst + r * yStep: one multiply-add per
  // vertex, and no drift over thousands of rows.
  std::vector<float> yFirst, yStep;
  std::vector<glm::vec3> frontOverW, backOverW;  // lit colour / w, two sides
  // The shading plan's extra attributes / w, extraCount per vertex.
  std::vector<float> extrasOverW;
  int extraCount = 0;
  // Triangles after near/far clipping (clipping adds vertices above).
  std::vector<glm::uvec3> triangles;
  std::vector<uint8_t> cullBack;  // per triangle: its material culls back faces
  std::vector<uint32_t> materials;  // per triangle: index into Scene::materials
  // Per triangle when slices are coloured by vectors, else empty: the
  // colours above are then unused.
  std::vector<SliceVector> vectors;
  shading::TextureVectors vectorTexels;
  std::vector<HighlightKnot> knots;

  size_t vertexCount() const { return x0.size(); }
  // Room for this many vertices and triangles (and texels of vectors),
  // so that builders appending millions do not copy as they grow.
  void reserve(size_t vertices, size_t triangleCount, size_t texels = 0);
  size_t bytes() const;
};

// The scene's triangles sorted by the world y of their centres and cut
// into runs of kSize, each with its world bounds: thin slabs across the
// image's scanlines, so that a process rendering a band of scanlines (its
// share of a split job) transforms only the triangles of runs whose image
// can reach the band. (Mesh order is not compact enough: a scanned mesh's
// runs of 256 span most of its height.)
struct TriangleRuns {
  static constexpr size_t kSize = 256;
  std::vector<uint32_t> order;  // triangle indices, run after run
  std::vector<Bounds> bounds;   // per run

  static TriangleRuns of(const Scene& scene);
  // Per triangle, whether its run's image can cross a scanline of the
  // camera's share in any of the share's rows: a box's projection lies
  // within its corners' when the box is wholly in front of the camera
  // plane (any other run is kept), and in a shearing camera y does not
  // depend on the view. Empty when the share has every scanline.
  std::vector<uint8_t> keptTriangles(const ShearingCamera& camera) const;
};

// Clips triangles to the near and far planes in world space (view
// independent: both planes are parallel to the camera plane), then
// transforms to row `row`'s extreme views. extras: extraCount floats per
// scene vertex (shading::vertexExtras), interpolated like the colours.
// With `runs`, only the triangles of runs reaching the camera's share are
// kept, and only their vertices transformed: the others keep zeroed slots
// so that indices stay the scene's. The kept triangles keep their mesh
// order, so the share's slices are the same.
ExtremeVertices transformToExtremes(const Scene& scene, const shading::VertexColors& colors,
                                    const ShearingCamera& camera, int row = 0,
                                    std::span<const float> extras = {}, int extraCount = 0,
                                    const TriangleRuns* runs = nullptr);

// Appends world points as extreme vertices of one row of views: what
// transformToExtremes does per vertex, for callers with points of their
// own (the image-based back end's source pixels).
class ExtremeTransform {
 public:
  ExtremeTransform(const ShearingCamera& cam, int row, ExtremeVertices& out);
  // Colours as lit; extras: out.extraCount floats (null when none).
  void add(const glm::dvec3& p, const glm::vec3& front, const glm::vec3& back, const float* extras);
  // A slot no triangle uses: zeros.
  void skip();
  bool inside(const glm::dvec3& p) const {  // between the near and far planes
    const double d = D_ - p.z;
    return d >= n_ && d <= f_;
  }
  double D() const { return D_; }
  double nearDistance() const { return n_; }
  double farDistance() const { return f_; }

 private:
  const ShearingCamera& cam_;
  ExtremeVertices& out_;
  double D_, n_, f_, sx_, sy_, cxLeft_, cxRight_, cy_, rowStep_;
  int firstRow_;
};

// Appends `from`'s vertices and triangles, with their vectors, texels and
// knots, after `to`'s (slices built in parallel, joined).
void appendVertices(ExtremeVertices& to, const ExtremeVertices& from);

// Moves the vertices to another row of views: y only.
void moveToRow(ExtremeVertices& vertices, int row);

}  // namespace mvr
