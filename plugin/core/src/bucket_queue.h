// Internal: the ADB traversal's priority queue — buckets by key, LIFO inside a bucket.
//
// A binary heap of 32-byte entries cost 103 instructions a node pair (sifting up on push and
// down on pop; callgrind on nodePairCost/adb before issue 26, docs/probability-model.md
// section 6). The keys are quantised anyway (priority_table.h), so a bucket per key value
// does: a push appends to its bucket and sets the bucket's bit in an occupancy mask, a pop
// takes the last entry of the highest occupied bucket (found with one count of leading
// zeros). Inside a bucket the newest pair comes first: the children of the pair just expanded,
// which is the depth-first order that reaches leaves soonest among equals. The buckets keep
// their capacity across queries: no allocation in steady state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace adb::detail {

template <class Entry, int Buckets>
class BucketQueue {
  static_assert(Buckets > 0 && Buckets <= 128, "two 64-bit occupancy words");

 public:
  void push(const Entry& e, int bucket) {
    m_buckets[bucket].push_back(e);
    m_occupied[bucket >> 6] |= std::uint64_t{1} << (bucket & 63);
    ++m_size;
  }

  bool empty() const { return m_size == 0; }
  std::size_t size() const { return m_size; }

  /// The highest occupied bucket; only when not empty.
  int top() const {
    if (m_occupied[1] != 0) return 127 - __builtin_clzll(m_occupied[1]);
    return 63 - __builtin_clzll(m_occupied[0]);
  }

  /// Takes the newest entry of the highest occupied bucket; only when not empty.
  Entry pop(int& bucket) {
    bucket = top();
    std::vector<Entry>& b = m_buckets[bucket];
    const Entry e = b.back();
    b.pop_back();
    if (b.empty()) m_occupied[bucket >> 6] &= ~(std::uint64_t{1} << (bucket & 63));
    --m_size;
    return e;
  }

  /// Room for `perBucket` entries in every bucket, so that a first query allocates no more
  /// than a later one would.
  void reserve(std::size_t perBucket) {
    for (std::vector<Entry>& b : m_buckets) b.reserve(perBucket);
  }

  void clear() {
    forEachBucket([](std::vector<Entry>& b, int) { b.clear(); });
    m_occupied[0] = m_occupied[1] = 0;
    m_size = 0;
  }

  /// f(bucket's entries, bucket) for every occupied bucket, highest first.
  template <class F>
  void forEachBucket(F&& f) {
    eachBucket(*this, f);
  }
  template <class F>
  void forEachBucket(F&& f) const {
    eachBucket(*this, f);
  }

  /// f(bucket's entries, bucket) for occupied buckets, highest first, while f returns true.
  template <class F>
  void forEachBucketWhile(F&& f) const {
    eachBucket(*this, f);
  }

  /// Removes the entries for which drop(entry) is true, keeping the others' order; returns
  /// how many went.
  template <class Drop>
  std::size_t removeIf(Drop&& drop) {
    std::size_t removed = 0;
    forEachBucket([&](std::vector<Entry>& b, int bucket) {
      std::size_t kept = 0;
      for (const Entry& e : b) {
        if (!drop(e)) b[kept++] = e;
      }
      removed += b.size() - kept;
      b.resize(kept);
      if (kept == 0) m_occupied[bucket >> 6] &= ~(std::uint64_t{1} << (bucket & 63));
    });
    m_size -= removed;
    return removed;
  }

  std::size_t capacityBytes() const {
    std::size_t bytes = 0;
    for (const std::vector<Entry>& b : m_buckets) bytes += b.capacity() * sizeof(Entry);
    return bytes;
  }

 private:
  template <class Self, class F>
  static void eachBucket(Self& self, F& f) {
    for (int word = 1; word >= 0; --word) {
      for (std::uint64_t bits = self.m_occupied[word]; bits != 0;) {
        const int bit = 63 - __builtin_clzll(bits);
        bits &= ~(std::uint64_t{1} << bit);
        // f may return whether to go on (forEachBucketWhile).
        if constexpr (std::is_same_v<decltype(f(self.m_buckets[0], 0)), bool>) {
          if (!f(self.m_buckets[word * 64 + bit], word * 64 + bit)) return;
        } else {
          f(self.m_buckets[word * 64 + bit], word * 64 + bit);
        }
      }
    }
  }

  std::vector<Entry> m_buckets[Buckets];
  std::uint64_t m_occupied[2] = {0, 0};
  std::size_t m_size = 0;
};

}  // namespace adb::detail
