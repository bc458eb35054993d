#pragma once
// Adler-32 (RFC 1950), the checksum ending every PNG's zlib stream, 32
// bytes a step with SSE2 instead of zlib's byte a step: it was a tenth of
// PNG encoding's time (docs/BENCHMARKS.md). The same value as zlib's
// adler32() for any input.
#include <cstdint>
#include <span>

namespace mvr {

// The checksum of the bytes before, carried on over `bytes` (1 for none).
uint32_t adler32Update(uint32_t adler, std::span<const uint8_t> bytes);

}  // namespace mvr
