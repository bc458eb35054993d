#pragma once
// Split tracks for specular highlights in the image-based back end (de
// Quilletes 2018). A source pixel's diffuse colour serves every view, but
// its highlight changes with the eye. It peaks where the light's mirror
// ray from the surface point passes the camera track: the closest
// approach of two lines, the ray and the track line. The track is split
// there and at K pairs of views either side where the highlight has
// fallen by 1/(K+1), 2/(K+1), ... of its peak (cos^s of the view's angle
// off the mirror ray); the highlight is evaluated exactly
// (shading::specularLight) at the splits and the track's ends and drawn
// linearly in the view between them, so its error is about 1/(K+1) of
// the peak at most.
#include <optional>
#include <vector>

#include "mvr/camera.h"
#include "mvr/scene.h"
#include "slicing/extreme_vertices.h"

namespace mvr {

// The camera x on the line y = trackY, z = trackZ closest to the ray
// p + t dir (t >= 0, dir unit length); none when the ray runs parallel to
// the line or away from it.
std::optional<double> closestTrackX(const glm::dvec3& p, const glm::dvec3& dir, double trackY,
                                    double trackZ, double* rayDistance = nullptr);

class HighlightSplitter {
 public:
  // splits: K pairs of split views per light around the peak.
  HighlightSplitter(const Scene& scene, const ShearingCamera& cam, int row, int splits);

  bool specular(uint32_t material) const;
  // Appends the knots of point p with unit normal n; returns how many.
  int add(const glm::vec3& p, const glm::vec3& n, uint32_t material,
          std::vector<HighlightKnot>& out) const;

 private:
  // The eye at EPI row coordinate r (view i at r = i + 0.5), and back.
  glm::vec3 eyeAt(float r) const { return glm::vec3(cam_.eye(r - 0.5, row_)); }
  float rowOf(double x) const { return float(0.5 + (x - cam_.viewX(0)) / cam_.viewSpacing()); }

  const Scene& scene_;
  const ShearingCamera& cam_;
  int row_, splits_;
};

}  // namespace mvr
