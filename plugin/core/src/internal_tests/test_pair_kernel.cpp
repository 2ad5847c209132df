// The pair kernel (pair_kernel.h) against the pair-at-a-time test it replaced
// (reference_child_pairs.h): on a million random node pairs of real trees, placed near each
// other so that about half overlap, and on pairs placed exactly touching, every output must be
// the reference's bit for bit: the overlap mask, the separations and depths, s, s_A, s_B and
// E[X]. Exact mode's answers depend on nothing else, which is how its pinned hash holds.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "pair_kernel.h"
#include "reference_child_pairs.h"
#include "relative_frame.h"
#include "test_support.h"

namespace adb {
namespace {

std::uint64_t bitsOf(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// The nodes an expansion of `n` tests: its children, or a leaf itself.
int childrenOf(const AdbTree& tree, std::uint32_t n, std::uint32_t out[2]) {
  const Node& node = tree.nodes()[n];
  if (node.isLeaf()) {
    out[0] = n;
    return 1;
  }
  out[0] = node.firstChild();
  out[1] = node.firstChild() + 1;
  return 2;
}

Vec3 centreOf(const AdbTree& tree, std::uint32_t n) {
  return 0.5 * (tree.nodes()[n].boxLo() + tree.nodes()[n].boxHi());
}
Vec3 halfOf(const AdbTree& tree, std::uint32_t n) {
  return 0.5 * (tree.nodes()[n].boxHi() - tree.nodes()[n].boxLo());
}

struct Comparison {
  long pairs = 0, overlapping = 0, mismatches = 0;
};

// Compares every output of one expansion; returns the pairs compared.
void compareExpansion(const AdbTree& ta, const std::uint32_t* ca, int countA, const AdbTree& tb,
                      const std::uint32_t* cb, int countB, const detail::RelativeFrame& frame,
                      Comparison& c) {
  detail::PairKernel kernel(ta, ca, countA, tb, cb, countB, frame);
  const unsigned mask = kernel.boxAndSlabMask();  // the reference has no cells
  double depth[4] = {};
  if (mask != 0) kernel.boxDepths(depth);
  detail::CellCounts counts[4];
  kernel.cellCounts(mask, counts);
  detail::PairKernel measured(ta, ca, countA, tb, cb, countB, frame);
  double separation[4] = {};
  const unsigned measuredMask = measured.measure(separation);
  reference::ChildPairs ref(ta, ca, countA, tb, cb, countB, frame);
  for (int i = 0; i < countA; ++i) {
    for (int j = 0; j < countB; ++j) {
      const int p = detail::PairKernel::index(i, j);
      ++c.pairs;
      const bool overlaps = ref.overlap(i, j);
      bool same = overlaps == (((mask >> p) & 1u) != 0);
      const reference::PairTest t = ref.test(i, j);
      same = same && t.overlaps == (((measuredMask >> p) & 1u) != 0) &&
             bitsOf(t.separation) == bitsOf(separation[p]);
      if (overlaps) {
        ++c.overlapping;
        same = same && bitsOf(ref.boxDepth(i, j)) == bitsOf(depth[p]);
        const detail::CellCounts r = reference::countsOverlapping(ref.a(i), ref.b(j));
        same = same && r.s == counts[p].s && r.sA == counts[p].sA && r.sB == counts[p].sB &&
               bitsOf(r.expected) == bitsOf(counts[p].expected);
      }
      if (!same) ++c.mismatches;
    }
  }
}

struct Trees {
  AdbTree knot{gen::makeModel("knot", 3000)};
  AdbTree gear{gen::makeModel("gears", 2000)};
};

const Trees& trees() {
  static const Trees t;
  return t;
}

// Random node pairs placed near each other: node b's centre within about one box size of node
// a's, at a random relative rotation (a quarter of them axis-aligned, where faces are parallel
// and the box tests decide alone).
TEST(PairKernel, MatchesThePairAtATimeTestOnAMillionRandomPairs) {
  const AdbTree& ta = trees().knot;
  const AdbTree& tb = trees().gear;
  std::mt19937_64 rng(test::kSeed);
  std::uniform_int_distribution<std::uint32_t> pickA(0, static_cast<std::uint32_t>(ta.nodes().size() - 1));
  std::uniform_int_distribution<std::uint32_t> pickB(0, static_cast<std::uint32_t>(tb.nodes().size() - 1));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Comparison c;
  while (c.pairs < 1000000) {
    const std::uint32_t a = pickA(rng), b = pickB(rng);
    const Pose poseA = Pose::fromQuaternion(randomRotation(rng), Vec3(u(rng), u(rng), u(rng)));
    Mat3 rel = Mat3::Identity();
    if (rng() % 4 != 0) rel = randomRotation(rng).toRotationMatrix();
    const double reach = (halfOf(ta, a) + halfOf(tb, b)).norm();
    const Vec3 target = centreOf(ta, a) + 0.7 * reach * Vec3(u(rng), u(rng), u(rng));
    Pose poseB;
    poseB.rotation = poseA.rotation * rel;
    poseB.translation = poseA.translation + poseA.rotation * (target + ta.origin()) -
                        poseB.rotation * (centreOf(tb, b) + tb.origin());
    const detail::RelativeFrame frame = detail::RelativeFrame::between(ta, poseA, tb, poseB);
    std::uint32_t ca[2], cb[2];
    const int countA = childrenOf(ta, a, ca);
    const int countB = childrenOf(tb, b, cb);
    compareExpansion(ta, ca, countA, tb, cb, countB, frame, c);
    compareExpansion(ta, &a, 1, tb, &b, 1, frame, c);  // a single pair (a root, a resumed pair)
  }
  EXPECT_EQ(c.mismatches, 0) << "of " << c.pairs << " pairs";
  // Both answers must be common, or the comparison proves little.
  EXPECT_GT(c.overlapping, c.pairs / 5);
  EXPECT_LT(c.overlapping, c.pairs * 4 / 5);
}

// Boxes whose faces touch exactly, axis-aligned: the tests sit on their tolerance.
TEST(PairKernel, MatchesThePairAtATimeTestOnTouchingBoxes) {
  const AdbTree& ta = trees().knot;
  const AdbTree& tb = trees().gear;
  std::mt19937_64 rng(test::kSeed + 1);
  std::uniform_int_distribution<std::uint32_t> pickA(0, static_cast<std::uint32_t>(ta.nodes().size() - 1));
  std::uniform_int_distribution<std::uint32_t> pickB(0, static_cast<std::uint32_t>(tb.nodes().size() - 1));
  Comparison c;
  for (int trial = 0; trial < 20000; ++trial) {
    const std::uint32_t a = pickA(rng), b = pickB(rng);
    const int axis = trial % 3;
    Vec3 offset = Vec3::Zero();
    offset[axis] = (trial % 2 == 0 ? 1.0 : -1.0) * (halfOf(ta, a)[axis] + halfOf(tb, b)[axis]);
    const Pose poseA;
    Pose poseB;
    poseB.translation = (centreOf(ta, a) + ta.origin() + offset) - (centreOf(tb, b) + tb.origin());
    const detail::RelativeFrame frame = detail::RelativeFrame::between(ta, poseA, tb, poseB);
    compareExpansion(ta, &a, 1, tb, &b, 1, frame, c);
  }
  EXPECT_EQ(c.mismatches, 0) << "of " << c.pairs << " pairs";
  EXPECT_GT(c.overlapping, c.pairs / 2);  // touching counts as overlapping
}

}  // namespace
}  // namespace adb
