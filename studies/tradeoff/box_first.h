// "box-first": a best-first traversal of the same ADB-trees ordered by box overlap alone, with
// no probability model. It is the baseline that tells whether ADB's probabilities pay for
// themselves: same tree, same leaf triangle test, same budgets, but the queue is ordered by
// a purely geometric measure and a cut query can only say "boxes still overlap".
//
//   queue = max-heap of node pairs keyed by the volume of the overlap of A's box with the
//           axis-aligned box of B's box mapped into A's frame (a purely geometric measure)
//   roots: admitted by the 15-axis oriented-box test of root_overlap.h (the study's own
//          root filter), so that a budget of 0 answers exactly like "root-boxes"
//   pop the largest; two leaves: test their triangles exactly (a hit is certain: collides)
//   otherwise every child pair (a leaf is its own only child) whose boxes overlap on the 6
//   face axes (A's box vs B's box mapped into A's frame, and the reverse) is queued
//
// Completed: the exact answer, confidence 1. Cut by the time budget, checked as the core
// checks it (the clock is read at the first pop and then whenever 64 units of work have
// accumulated, 4 per popped pair and 1 per triangle test): "collides" while any pair is
// still queued (the best a method without probability can say), confidence 0.5 (no
// estimate).
//
// Not handicapped against ADB: each expansion maps each child's box into the other frame
// once (a child meets both children of the other node), and a leaf pair maps B's triangles
// into A's frame and boxes both leaves' triangles once, as the core's leaf test does.
// Tree A is the first model's and tree B the second's (the same tree for two copies).
//
// Uses only the public API of adb::AdbTree. The queue lives in the method and is reused,
// so queries do not allocate once it has grown to a query's size.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "adb/core/tree.h"
#include "adb_method.h"
#include "method.h"

namespace adb::tradeoff {

class BoxFirstMethod : public Method {
 public:
  /// `budgetUs`: wall-clock budget in microseconds (>= 0; infinity: run to the end).
  BoxFirstMethod(std::shared_ptr<SharedTree> shared, double budgetUs);

  const std::string& name() const override { return m_name; }
  MethodParams params() const override;
  void prepare(const Model& a, const Model& b) override;
  Answer query(const Pose& a, const Pose& b) override;

  /// The clock is read at the first pop and then once this much work has accumulated since
  /// the last read, counting kWorkPerPair per popped pair and 1 per triangle test (the
  /// core's rule, plugin/core/src/query.cpp, so that both overshoot a budget alike).
  static constexpr std::uint32_t kClockWork = 64;
  static constexpr std::uint32_t kWorkPerPair = 4;

 private:
  struct Entry {
    double key;  ///< overlap volume of the two boxes in A's frame
    std::uint32_t a, b;  ///< a node of tree A, a node of tree B
  };
  struct Frame;   // B's tree-local frame seen from A's
  struct Budget;  // the time budget and the work done since the clock was last read

  static bool heapLess(const Entry& x, const Entry& y) { return x.key < y.key; }
  Frame frameBetween(const Pose& a, const Pose& b) const;
  /// Tests the triangles of two leaves; counts each triangle test in `budget`.
  bool leavesIntersect(const Node& na, const Node& nb, const Frame& f, Budget& budget) const;
  /// Queues the overlapping child pairs of a popped pair of nodes, not both leaves.
  void pushOverlappingChildren(const Entry& e, const Frame& f, std::int64_t& nodePairs);
  /// Expands a popped pair: queues its overlapping child pairs, or tests two leaves.
  /// Returns true on an intersecting triangle pair.
  bool expand(const Entry& e, const Frame& f, Budget& budget, std::int64_t& nodePairs);

  std::shared_ptr<SharedTree> m_shared;
  double m_budgetUs;
  std::string m_name = "box-first";
  const AdbTree* m_treeA = nullptr;
  const AdbTree* m_treeB = nullptr;
  Aabb m_boundsA, m_boundsB;   ///< the meshes' bounding boxes, for the root test
  std::vector<Entry> m_heap;   ///< scratch, kept between queries
};

}  // namespace adb::tradeoff
