#pragma once
// The scanline slice table (Halle 6.4.2): for every scanline, the horizontal
// slices of the triangles that cross its centre y = j + 0.5. A slice is
// compact: its triangle, two screen-space edge parameters and a flag word;
// the endpoints are evaluated from the extreme vertices when needed.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/camera.h"
#include "slicing/extreme_vertices.h"

namespace mvr {

struct Slice {
  uint32_t triangle;
  float tLong;   // along the long edge top -> bottom (vertices a -> c)
  float tShort;  // along a -> b (upper half) or b -> c (lower half)
  uint32_t flags;
  // flags: bits 0-5 the triangle corners sorted by y (a, b, c; 2 bits
  // each), bit 6 lower half (short edge b -> c), bit 7 endpoints swapped,
  // bit 8 a segment: the "triangle" (a, b, -) is a horizontal run whose
  // endpoints are its vertices a and b (image-based slices).
};
constexpr uint32_t kSegmentSlice = 1u << 8;
static_assert(sizeof(Slice) == 16);

// One slice endpoint: a fixed 3D point, so its EPI track is a line.
struct SliceEnd {
  float x0, dx;    // x at row coordinate r is x0 + (r - 0.5) dx
  float depth;     // window depth, shared by all views
  float invW;      // 1 / w
  glm::vec3 frontOverW, backOverW;
  std::array<float, shading::kMaxExtras> extrasOverW;  // ExtremeVertices::extraCount used
};

class SliceTable {
 public:
  int height() const { return int(offsets_.size()) - 1; }
  std::span<const Slice> scanline(int j) const {
    return {slices_.data() + offsets_[j], slices_.data() + offsets_[j + 1]};
  }
  size_t sliceCount() const { return slices_.size(); }
  size_t bytes() const { return slices_.size() * sizeof(Slice) + offsets_.size() * sizeof(uint32_t); }
  // The flat arrays: height + 1 prefix sums, and every slice in scanline
  // order (the layout GPU buffers hold too).
  std::span<const uint32_t> offsets() const { return offsets_; }
  std::span<const Slice> slices() const { return slices_; }
  // A table from those arrays (offsets non-decreasing from 0 to the slice
  // count); throws mvr::Error otherwise.
  static SliceTable fromArrays(std::vector<uint32_t> offsets, std::vector<Slice> slices);

  // Builds the table in `bands` bands of scanlines (0: one per pool
  // worker), each task owning its band: no locks, no sort, slices in
  // triangle order per scanline whatever the band count.
  static SliceTable build(const ExtremeVertices& v, int height, int bands = 0);
  // The same with slices only on the given scanlines (a process's share of
  // a split job); the others are empty.
  static SliceTable build(const ExtremeVertices& v, int height, IndexRange scanlines, int bands = 0);
  // A table of segments: v's triangle k is the segment from its vertex x
  // to its vertex y, on scanline scanlineOf[k].
  static SliceTable fromSegments(const std::vector<uint32_t>& scanlineOf, int height);
  // The slices whose triangle `keep` accepts, in the same order.
  template <class Keep>
  SliceTable keeping(Keep keep) const {
    SliceTable table;
    table.offsets_.reserve(offsets_.size());
    table.offsets_.push_back(0);
    for (int j = 0; j < height(); ++j) {
      for (const Slice& s : scanline(j))
        if (keep(s.triangle)) table.slices_.push_back(s);
      table.offsets_.push_back(uint32_t(table.slices_.size()));
    }
    return table;
  }

 private:
  std::vector<uint32_t> offsets_;  // height + 1 prefix sums
  std::vector<Slice> slices_;
};

// Endpoints 0 and 1 of a slice, ordered so that x1 - x0 > 0 exactly in the
// views where the triangle faces the camera.
std::pair<SliceEnd, SliceEnd> sliceEnds(const ExtremeVertices& v, const Slice& s);

// The scanlines [first, last) whose centres a triangle with these y values
// covers: centre y = j + 0.5 with ymin <= centre < ymax.
std::pair<int, int> scanlineRange(float y0, float y1, float y2, int height);

}  // namespace mvr
