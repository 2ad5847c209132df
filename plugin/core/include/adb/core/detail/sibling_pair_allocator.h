// Internal to adb/core/tree.h: the allocator of the tree's node arrays (NodeArray). Part of
// their type, hence a header; not part of the API.
#pragma once

#include <cstddef>
#include <new>

namespace adb::detail {

/// Places element 1 of an array of 32-byte records at a 64-byte boundary. The builder
/// allocates siblings as pairs (2k + 1, 2k + 2) after the root at 0, and a traversal reads
/// both children of a node together: with this offset each pair shares one cache line
/// instead of straddling two.
template <class T>
struct SiblingPairAllocator {
  static_assert(sizeof(T) == 32, "two records per cache line");
  using value_type = T;
  static constexpr std::size_t kLine = 64;
  SiblingPairAllocator() = default;
  template <class U>
  SiblingPairAllocator(const SiblingPairAllocator<U>&) {}
  T* allocate(std::size_t n) {
    void* line = ::operator new(n * sizeof(T) + kLine, std::align_val_t(kLine));
    return reinterpret_cast<T*>(static_cast<char*>(line) + sizeof(T));
  }
  void deallocate(T* p, std::size_t) {
    ::operator delete(reinterpret_cast<char*>(p) - sizeof(T), std::align_val_t(kLine));
  }
  template <class U>
  bool operator==(const SiblingPairAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const SiblingPairAllocator<U>&) const { return false; }
};

}  // namespace adb::detail
