#pragma once
// Memory for large buffers (a view row's frames, a quilt) on the kernel's
// transparent huge pages where it gives them on request (its "madvise"
// mode, Debian's default): a 45 MB quilt is first touched in 22 faults of
// 2 MiB instead of 11,000 of 4 KiB. A fault costs about 8 us on the 2-core
// VMs here, and a process's first frame of a Portrait quilt spent 0.17 s
// in them. Small buffers are operator new's, as std::allocator's are.
#include <cstddef>

namespace mvr {

// At least `bytes`, aligned for any type; free with freeLarge(p, bytes).
void* allocateLarge(size_t bytes);
void freeLarge(void* p, size_t bytes);

template <class T>
struct LargePageAllocator {
  using value_type = T;
  LargePageAllocator() = default;
  template <class U>
  LargePageAllocator(const LargePageAllocator<U>&) {}  // NOLINT: allocators convert implicitly
  T* allocate(size_t n) { return static_cast<T*>(allocateLarge(n * sizeof(T))); }
  void deallocate(T* p, size_t n) { freeLarge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const LargePageAllocator<U>&) const { return true; }
};

}  // namespace mvr
