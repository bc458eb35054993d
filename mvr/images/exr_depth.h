#pragma once
// Depth maps written as OpenEXR files by our own encoder, not through the
// OpenImageIO module: `mvr render --depth` writes one per view, and with
// PNG colour the module (0.27 s to load) and OpenEXR's zlib (5 ms a
// 640x480 map) were most of what the depth pass cost beside rendering
// (docs/BENCHMARKS.md). The file: a single-part scanline image, one FLOAT
// channel "Z", ZIP compression (blocks of 16 scanlines, each interleaved
// and delta-predicted as OpenEXR's ZIP codec defines, then deflated by our
// row coder, mvr/images/row_deflate.h, as a zlib stream) or none; OpenEXR's
// reader takes it like any other.
#include <vector>

#include "mvr/image.h"

namespace mvr {

// The file's bytes into out (replaced). zip false: NO_COMPRESSION.
void encodeDepthExr(const DepthImage& depth, bool zip, std::vector<unsigned char>& out);

}  // namespace mvr
