// Internal to adb/bullet/mesh_shape.h: the flag behind MeshData's once-only warning. Part of
// MeshData's layout, hence a header; not part of the API.
#pragma once

#include <atomic>

namespace adb::detail {

/// A flag raised at most once, from any thread (a warning given once per MeshData). Copies
/// start lowered, so MeshData stays copyable and movable.
class OnceFlag {
 public:
  OnceFlag() = default;
  OnceFlag(const OnceFlag&) noexcept {}
  OnceFlag& operator=(const OnceFlag&) noexcept { return *this; }
  /// True the first time only.
  bool raise() const noexcept { return !m_raised.exchange(true, std::memory_order_relaxed); }

 private:
  mutable std::atomic<bool> m_raised{false};
};

}  // namespace adb::detail
