#include "mvr/large_pages.h"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace mvr {
namespace {

constexpr size_t kHugePage = size_t(2) << 20;
// Below this a buffer stays on ordinary pages: rounding it up to whole
// huge pages would waste up to half of it.
constexpr size_t kLarge = size_t(4) << 20;

size_t rounded(size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }

}  // namespace

void* allocateLarge(size_t bytes) {
  if (bytes < kLarge) return ::operator new(bytes);
  void* p = std::aligned_alloc(kHugePage, rounded(bytes));
  if (!p) throw std::bad_alloc();
  // Advice only: a kernel without huge pages leaves the memory as it is.
  (void)madvise(p, rounded(bytes), MADV_HUGEPAGE);
  return p;
}

void freeLarge(void* p, size_t bytes) {
  if (bytes < kLarge)
    ::operator delete(p);
  else
    std::free(p);
}

}  // namespace mvr
