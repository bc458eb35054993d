#pragma once
// Exclusive prefix sums of uints in a GPU buffer, by compute shaders: the
// step that turns per-item counts into output offsets, so that passes
// which emit a variable number of things per item (slices per triangle,
// vertices per slice) can write them in order without the CPU. Blocks of
// 1024 elements, block sums scanned recursively (three levels reach 2^30
// elements).
#include <cstdint>
#include <vector>

#include "mvr/gl/gl_handles.h"

namespace mvr::gl {

class PrefixSum {
 public:
  PrefixSum();  // needs a current GL context

  // Replaces count uints starting at element `first` of `data` by their
  // exclusive prefix sums; writes the sum of all of them as one uint at
  // byte `totalAt` of `totalBuffer`. Issues the shader-storage and command
  // barriers its results need before they are read by shaders, draws or
  // buffer copies.
  void exclusive(GLuint data, uint32_t first, uint32_t count, GLuint totalBuffer, GLintptr totalAt);

  // A grid of `rows` rows of `stride` counts, row-major from element 0
  // of `data`: scans it as exclusive() does and writes rows + 1 uints to
  // `out`, the first slot of each row and then the total (the offsets of
  // a slice table whose rows are scanlines).
  void exclusiveRows(GLuint data, uint32_t rows, uint32_t stride, GLuint out);

  static constexpr uint32_t kBlock = 1024;

 private:
  // Scans count elements at `first` of data; returns the buffer whose
  // element 0 holds their total.
  GLuint scan(GLuint data, uint32_t first, uint32_t count, size_t level);

  Program scan_, add_, rowStarts_;
  std::vector<Buffer> sums_;  // per level: one uint per block
  std::vector<size_t> sumsSize_;
};

}  // namespace mvr::gl
