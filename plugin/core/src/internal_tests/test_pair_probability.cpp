// The node-pair probability (detail::estimatePair, paper §3.5-3.6, docs/probability-model.md
// section 4) on real trees: against a Monte Carlo simulation of the cell model written here
// from the document, against cases computed by hand, and invariants over random pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/probability.h"
#include "adb/core/tree.h"
#include "adb/core/triangle_test.h"
#include "pair_probability.h"
#include "test_support.h"

namespace adb {
namespace {

// ---- Trees with node depths -------------------------------------------------------------

struct DepthTree {
  AdbTree tree;
  std::vector<int> depth;           // per node
  std::vector<std::vector<std::uint32_t>> byDepth;  // node indices per depth

  explicit DepthTree(const TriangleMesh& mesh, const BuildSettings& settings = {})
      : tree(mesh, settings), depth(tree.nodes().size(), 0) {
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      if (static_cast<int>(byDepth.size()) <= depth[i]) byDepth.resize(depth[i] + 1);
      byDepth[depth[i]].push_back(i);
      const Node& n = tree.nodes()[i];
      if (n.isLeaf()) continue;
      for (std::uint32_t c : {n.firstChild(), n.firstChild() + 1}) {
        depth[c] = depth[i] + 1;
        stack.push_back(c);
      }
    }
  }
  detail::TreeConstants constants() const { return {&tree, tree.maxDepth()}; }
  Vec3 centre(std::uint32_t i) const {
    return 0.5 * (tree.nodes()[i].boxLo() + tree.nodes()[i].boxHi());
  }
  Vec3 half(std::uint32_t i) const {
    return 0.5 * (tree.nodes()[i].boxHi() - tree.nodes()[i].boxLo());
  }
};

detail::PairEstimate estimate(const DepthTree& a, std::uint32_t ia, const Pose& poseA,
                              const DepthTree& b, std::uint32_t ib, const Pose& poseB) {
  const detail::RelativeFrame frame = detail::RelativeFrame::between(a.tree, poseA, b.tree,
                                                                     poseB);
  // The model's estimate of two overlapping boxes: the boxes and slabs decide the overlap
  // here, not the occupied cells, which would part some of the hand-built pairs.
  detail::PairKernel pair(a.tree, &ia, 1, b.tree, &ib, 1, frame);
  if (pair.boxAndSlabMask() == 0) return detail::PairEstimate{};
  detail::CellCounts counts[4];
  pair.cellCounts(1u, counts);
  return detail::estimateOverlapping(counts[0], a.depth[ia], b.depth[ib], a.tree.maxDepth(),
                                     b.tree.maxDepth());
}

// The pose of tree B that puts B's local point `pointB` at A's local point `targetA`, B's
// local axes turned by `rel` against A's.
Pose placeB(const DepthTree& a, const Pose& poseA, const DepthTree& b, const Vec3& pointB,
            const Mat3& rel, const Vec3& targetA) {
  Pose p;
  p.rotation = poseA.rotation * rel;
  p.translation = poseA.translation + poseA.rotation * (targetA + a.tree.origin()) -
                  p.rotation * (pointB + b.tree.origin());
  return p;
}

Pose randomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  return Pose::fromQuaternion(randomRotation(rng), Vec3(u(rng), u(rng), u(rng)));
}

// ---- The cell model, from docs/probability-model.md section 4 ---------------------------

// The AABB, in tree `to`'s local frame, of the 8 corners of node i of tree `from`.
Aabb mappedBox(const DepthTree& from, const Pose& poseFrom, std::uint32_t i,
               const DepthTree& to, const Pose& poseTo) {
  const Node& n = from.tree.nodes()[i];
  Aabb box;
  for (int corner = 0; corner < 8; ++corner) {
    Vec3 x;
    for (int k = 0; k < 3; ++k) x[k] = (corner >> k) & 1 ? n.hi[k] : n.lo[k];
    const Vec3 world = poseFrom.rotation * (x + from.tree.origin()) + poseFrom.translation;
    box.grow(poseTo.rotation.transpose() * (world - poseTo.translation) - to.tree.origin());
  }
  return box;
}

// Common cells of side h over the intersection of node i's box with `other`, at least one
// per axis (section 4, step 2), before rounding.
double commonCells(const DepthTree& t, std::uint32_t i, const Aabb& other, double h) {
  const Node& n = t.tree.nodes()[i];
  double cells = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double extent = std::min<double>(n.hi[k], other.hi[k]) -
                          std::max<double>(n.lo[k], other.lo[k]);
    cells *= std::max(1.0, extent / h);
  }
  return cells;
}

int roundHalfUp(double x) { return static_cast<int>(std::floor(x + 0.5)); }

struct CellModel {
  double h = 0.0;       // common cell side
  double sReal = 0.0;   // common cells before rounding
  int s = 0, sA = 0, sB = 0;
  double rhoA = 0.0, rhoB = 0.0;  // densities at the common cell size
  double lb = 0.0;                // LB = (dA + dB) / (dmaxA + dmaxB)
};

CellModel cellModel(const DepthTree& a, std::uint32_t ia, const Pose& poseA,
                    const DepthTree& b, std::uint32_t ib, const Pose& poseB) {
  const NodeDistribution& da = a.tree.distributions()[ia];
  const NodeDistribution& db = b.tree.distributions()[ib];
  CellModel m;
  m.h = std::max<double>(da.side, db.side);
  m.sReal = std::min(commonCells(a, ia, mappedBox(b, poseB, ib, a, poseA), m.h),
                     commonCells(b, ib, mappedBox(a, poseA, ia, b, poseB), m.h));
  m.s = std::clamp(roundHalfUp(m.sReal), 1, kMaxBins);
  m.rhoA = std::min(1.0, da.density * m.h / da.side);
  m.rhoB = std::min(1.0, db.density * m.h / db.side);
  m.sA = std::clamp(roundHalfUp(m.rhoA * m.s), 0, m.s);
  m.sB = std::clamp(roundHalfUp(m.rhoB * m.s), 0, m.s);
  const int den = a.tree.maxDepth() + b.tree.maxDepth();
  m.lb = den > 0 ? static_cast<double>(a.depth[ia] + b.depth[ib]) / den : 0.0;
  return m;
}

// `got` is a correct rounding of `real`: the nearest integer, or either neighbour when `real`
// is within rounding noise of a half-integer. Sides and densities are stored in float, so the
// implementation may form the same products with a relative error of a few float ulps: 1e-6.
bool roundsTo(int got, double real) {
  if (got == roundHalfUp(real)) return true;
  const double noise = 1e-6 * std::max(1.0, real);
  return std::abs(real - std::floor(real) - 0.5) < noise && std::abs(got - real) < 0.5 + noise;
}

// Monte Carlo of the cell model: sA distinct cells for A and sB for B, each drawn uniformly
// without replacement from s cells; X = cells holding one of each. Returns the estimated
// Pr[X >= x] for x = 0..kMaxCollisionCells.
std::vector<double> simulateTail(int s, int sA, int sB, int trials, std::mt19937_64& rng) {
  std::vector<int> cells(static_cast<std::size_t>(s));
  std::iota(cells.begin(), cells.end(), 0);
  std::vector<char> taken(static_cast<std::size_t>(s), 0);
  std::vector<int> atLeast(kMaxCollisionCells + 1, 0);
  for (int trial = 0; trial < trials; ++trial) {
    // Partial Fisher-Yates: A's cells, then an independent draw for B's.
    for (int i = 0; i < sA; ++i) {
      std::swap(cells[i], cells[std::uniform_int_distribution<int>(i, s - 1)(rng)]);
      taken[cells[i]] = 1;
    }
    std::vector<int> marked(cells.begin(), cells.begin() + sA);
    int x = 0;
    for (int i = 0; i < sB; ++i) {
      std::swap(cells[i], cells[std::uniform_int_distribution<int>(i, s - 1)(rng)]);
      x += taken[cells[i]];
    }
    for (int c : marked) taken[c] = 0;
    for (int k = 0; k <= std::min(x, kMaxCollisionCells); ++k) ++atLeast[k];
  }
  std::vector<double> tail(atLeast.size());
  for (std::size_t k = 0; k < tail.size(); ++k) tail[k] = static_cast<double>(atLeast[k]) / trials;
  return tail;
}

// Eq. 3 from a tail: max over 1 <= x <= min(sA, sB, 10) of Pr[X >= x] (1 - (1 - LB)^x).
double eq3(const std::vector<double>& tail, int sA, int sB, double lb) {
  double best = 0.0;
  for (int x = 1; x <= std::min({sA, sB, kMaxCollisionCells}); ++x) {
    best = std::max(best, tail[x] * (1.0 - std::pow(1.0 - lb, x)));
  }
  return best;
}

// Pr[X >= x] of the model in closed form (hypergeometric, log-gamma): for the hand cases.
std::vector<double> closedFormTail(int s, int sA, int sB) {
  const auto lnChoose = [](int n, int k) {
    return std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0);
  };
  std::vector<double> tail(kMaxCollisionCells + 1, 0.0);
  double below = 0.0;  // Pr[X < x]
  for (int x = 0; x <= kMaxCollisionCells; ++x) {
    tail[x] = 1.0 - below;
    if (x <= std::min(sA, sB) && sB - x <= s - sA) {
      below += std::exp(lnChoose(sA, x) + lnChoose(s - sA, sB - x) - lnChoose(s, sB));
    }
  }
  return tail;
}

// ---- Meshes -----------------------------------------------------------------------------

const DepthTree& torusTree() {
  static const DepthTree t(gen::makeTorus(1.0, 0.35, 32, 16));  // 1024 triangles
  return t;
}
const DepthTree& sphereTree() {
  static const DepthTree t(gen::makeSphere(1.0, 7));  // 980 triangles
  return t;
}
const DepthTree& flatTree() {
  static const DepthTree t(gen::makeFlatGrid(2.0, 2.0, 16, 16));  // 512 triangles
  return t;
}

BuildSettings exactCounting() {
  BuildSettings s;
  s.counting = CellCounting::Exact;
  return s;
}

// Two flat patches 10 * scale apart along x, each 3.2 x 1.6 (times scale) in z = 0: a strip of
// width 0.1 * scale covering the patch's left edge plus one tiny triangle in the opposite
// corner that only stretches the box. With G = 8 a patch gets 32 x 16 cells of side 0.1 *
// scale, of which the strip covers exactly one column: pc = 16, density 1/32.
TriangleMesh stripPatches(double scale) {
  const TriangleMesh strip = gen::makeFlatGrid(0.1 * scale, 1.6 * scale, 1, 16);
  const double e = 1e-3 * scale;
  const TriangleMesh tiny({Vec3(1.6 * scale, 0.8 * scale, 0.0),
                           Vec3(1.6 * scale - e, 0.8 * scale, 0.0),
                           Vec3(1.6 * scale, 0.8 * scale - e, 0.0)},
                          {Triangle{0, 1, 2}});
  const auto shifted = [](const TriangleMesh& m, double x) {
    return gen::transformed(m, Pose{Mat3::Identity(), Vec3(x, 0.0, 0.0)});
  };
  std::vector<TriangleMesh> parts;
  for (double c : {-5.0 * scale, 5.0 * scale}) {
    parts.push_back(shifted(strip, c - 1.55 * scale));
    parts.push_back(shifted(tiny, c));
  }
  return gen::merge(parts, "strip patches");
}

// The depth-1 node holding the patch at x < 0.
std::uint32_t leftPatch(const DepthTree& t) {
  const std::uint32_t c = t.tree.root().firstChild();
  return t.centre(c).x() < 0.0 ? c : c + 1;
}

// ---- Monte Carlo ------------------------------------------------------------------------

// Trials per Monte Carlo case. An estimated proportion p has standard error
// sqrt(p (1 - p) / kTrials) (at most 0.0035 here); every comparison allows 5 of them, so a
// case fails by chance with probability ~6e-7 per compared value.
constexpr int kTrials = 20000;
constexpr double kStandardErrors = 5.0;

double standardError(double p) {
  return std::sqrt(std::max(p * (1.0 - p), 1.0 / kTrials) / kTrials);
}

enum class Placement { BarelyTouching, HalfOverlapping, Centred };

const char* name(Placement p) {
  switch (p) {
    case Placement::BarelyTouching: return "barely touching";
    case Placement::HalfOverlapping: return "half overlapping";
    case Placement::Centred: return "centred (nested when smaller)";
  }
  return "";
}

// Where to put the centre of b's box in A's frame: along A's longest box axis, the boxes
// overlap by 4 % (barely touching) or 50 % (half overlapping) of the shorter of the two
// extents along that axis, or share their centre.
Vec3 targetFor(const DepthTree& a, std::uint32_t ia, const DepthTree& b, std::uint32_t ib,
               const Mat3& rel, Placement placement) {
  const Vec3 hA = a.half(ia);
  const Vec3 hB = rel.cwiseAbs() * b.half(ib);  // b's half extents seen on A's axes
  int k = 0;
  hA.maxCoeff(&k);
  const double shorter = std::min(hA[k], hB[k]);
  Vec3 target = a.centre(ia);
  if (placement == Placement::BarelyTouching) target[k] += hA[k] + hB[k] - 0.04 * 2 * shorter;
  if (placement == Placement::HalfOverlapping) target[k] += hA[k] + hB[k] - 0.5 * 2 * shorter;
  return target;
}

// Checks s, s_A, s_B of `e` against the model's definition (section 4, steps 1-4).
void expectCountsMatchTheModel(const detail::PairEstimate& e, const CellModel& m) {
  EXPECT_TRUE(roundsTo(e.s, std::clamp(m.sReal, 1.0, static_cast<double>(kMaxBins))))
      << "s " << e.s << " model " << m.sReal;
  EXPECT_TRUE(roundsTo(e.sA, m.rhoA * e.s)) << "sA " << e.sA << " model " << m.rhoA * e.s;
  EXPECT_TRUE(roundsTo(e.sB, m.rhoB * e.s)) << "sB " << e.sB << " model " << m.rhoB * e.s;
  // E[X] = rho_A rho_B s before rounding s_A, s_B, uncapped (the collision cells expected;
  // the traversal caps it only where it bounds a probability). Relative tolerance: densities
  // and sides are stored in float.
  const double expected = m.rhoA * m.rhoB * e.s;
  EXPECT_NEAR(e.expected, expected, 1e-6 * std::max(1.0, expected));
}

// estimatePair's Pr[X >= 1] and Eq. 3 agree with a Monte Carlo of the cell model on real
// trees (torus, sphere, flat grid) at depths 1-7, for boxes barely touching, half overlapping
// and centred (nested), and its s, s_A, s_B and E[X] agree with the model's definition.
// Tolerance: 5 standard errors of the simulated proportion (kTrials trials); for Eq. 3, the
// largest over x of 5 standard errors of Pr[X >= x] times its factor 1 - (1 - LB)^x, since a
// maximum moves by at most the largest error among its terms.
TEST(PairProbability, MatchesMonteCarloOfTheCellModel) {
  std::mt19937_64 rng(test::kSeed);
  struct Combo {
    const DepthTree* a;
    const DepthTree* b;
    int depthA, depthB;
    bool rotate;  // random relative rotation; coplanar flat grids otherwise
  };
  const Combo combos[] = {
      {&torusTree(), &sphereTree(), 1, 1, true}, {&torusTree(), &sphereTree(), 2, 3, true},
      {&sphereTree(), &torusTree(), 3, 2, true}, {&torusTree(), &torusTree(), 4, 4, true},
      {&sphereTree(), &flatTree(), 2, 4, true},  {&flatTree(), &flatTree(), 1, 3, false},
      {&flatTree(), &torusTree(), 3, 5, true},   {&sphereTree(), &sphereTree(), 5, 5, true},
      {&torusTree(), &sphereTree(), 6, 6, true}, {&sphereTree(), &torusTree(), 7, 6, true},
      {&torusTree(), &torusTree(), 7, 7, true},
  };
  int compared = 0, upperInside = 0, lowerInside = 0;
  for (int round = 0; round < 2; ++round) {  // two nodes of each kind: two draws per case
    for (const Combo& c : combos) {
      for (Placement placement :
           {Placement::BarelyTouching, Placement::HalfOverlapping, Placement::Centred}) {
        // A node with possible collision cells at each requested depth.
        const auto pick = [&rng](const DepthTree& t, int d) {
          std::vector<std::uint32_t> candidates;
          for (std::uint32_t i : t.byDepth.at(d)) {
            if (t.tree.distributions()[i].density > 0.0f) candidates.push_back(i);
          }
          return candidates.at(std::uniform_int_distribution<std::size_t>(
              0, candidates.size() - 1)(rng));
        };
        const std::uint32_t ia = pick(*c.a, c.depthA), ib = pick(*c.b, c.depthB);
        const Mat3 rel = c.rotate ? randomRotation(rng).toRotationMatrix() : Mat3::Identity();
        const Pose poseA = randomPose(rng);
        const Pose poseB = placeB(*c.a, poseA, *c.b, c.b->centre(ib), rel,
                                  targetFor(*c.a, ia, *c.b, ib, rel, placement));
        const detail::PairEstimate e = estimate(*c.a, ia, poseA, *c.b, ib, poseB);
        SCOPED_TRACE(testing::Message() << "depths " << c.depthA << "/" << c.depthB << ", "
                                        << name(placement) << ": s " << e.s << " sA " << e.sA
                                        << " sB " << e.sB);
        if (!e.overlap) continue;  // the slab test may separate boxes that touch
        const CellModel m = cellModel(*c.a, ia, poseA, *c.b, ib, poseB);
        expectCountsMatchTheModel(e, m);

        // The simulation runs on the model's own counts, not the implementation's.
        const std::vector<double> tail = simulateTail(m.s, m.sA, m.sB, kTrials, rng);
        const double upper = m.sA > 0 && m.sB > 0 ? tail[1] : 0.0;
        const double lower = eq3(tail, m.sA, m.sB, m.lb);
        double lowerTolerance = 0.0;
        for (int x = 1; x <= std::min({m.sA, m.sB, kMaxCollisionCells}); ++x) {
          lowerTolerance = std::max(lowerTolerance, kStandardErrors * standardError(tail[x]) *
                                                        (1.0 - std::pow(1.0 - m.lb, x)));
        }
        EXPECT_NEAR(e.upper, upper, kStandardErrors * standardError(upper));
        EXPECT_NEAR(e.lower, lower, lowerTolerance + 1e-12);
        ++compared;
        if (e.upper > 0.02 && e.upper < 0.98) ++upperInside;
        if (e.lower > 0.02 && e.lower < 0.98) ++lowerInside;
      }
    }
  }
  // Most of the 66 cases overlap (a slab may separate barely touching boxes), and enough of
  // them lie well inside (0, 1) for the comparison to mean something (31, 6 and 25 of 33 when
  // written; 29, 2 and 24 of 33 once the trees were built by SAH, issue 37, hence two draws).
  EXPECT_GE(compared, 50);
  EXPECT_GE(upperInside, 4);
  EXPECT_GE(lowerInside, 24);
}

// ---- Hand-computed cases ----------------------------------------------------------------

// Two identical, fully covered flat nodes exactly on top of each other (the same node of two
// copies of one tree, both posed alike). A flat node's grid has side h = sqrt(e_x e_y / 512),
// so its own box holds s = (e_x / h)(e_y / h) = 512 common cells; counted exactly, every cell
// is covered (density 1), so s_A = s_B = 512 and X = 512 surely: Pr[X >= 1] = 1 and Eq. 3 is
// 1 - (1 - LB)^10 with LB = 2d / (2 dmax) = d / dmax.
TEST(PairProbability, IdenticalFlatNodesOnTopOfEachOther) {
  const DepthTree t(gen::makeFlatGrid(3.2, 1.6, 32, 16), exactCounting());
  std::mt19937_64 rng(test::kSeed);
  const Pose pose = randomPose(rng);
  int checked = 0;
  for (std::uint32_t i = 0; i < t.tree.nodes().size(); ++i) {
    const Vec3 e = 2.0 * t.half(i);
    // Only nodes whose triangles cover their box (a leaf may hold half squares).
    if (std::abs(t.tree.surfaces()[i].area - e.x() * e.y()) > 1e-5 * e.x() * e.y()) continue;
    const double lb = static_cast<double>(t.depth[i]) / t.tree.maxDepth();
    const detail::PairEstimate est = estimate(t, i, pose, t, i, pose);
    SCOPED_TRACE(testing::Message() << "node " << i << " depth " << t.depth[i]);
    ASSERT_TRUE(est.overlap);
    EXPECT_EQ(est.s, 512);
    EXPECT_EQ(est.sA, 512);
    EXPECT_EQ(est.sB, 512);
    EXPECT_DOUBLE_EQ(est.upper, 1.0);
    EXPECT_NEAR(est.lower, 1.0 - std::pow(1.0 - lb, 10), 1e-12);
    // E[X] = 1 * 1 * 512 collision cells, to float storage (densities, 1 / side).
    EXPECT_NEAR(est.expected, 512.0, 512.0 * 1e-6);
    ++checked;
  }
  EXPECT_GE(checked, 400);  // of 511 nodes (all of them when written)
}

// The root of the same 3.2 x 1.6 grid (32 x 16 cells of side 0.1) against itself shifted in
// its plane along x. Half a box: s = 16 x 16 = 256. Overlapping by half a cell, or touching
// at an edge: at least one cell per axis, s = 1 x 16 = 16. Density 1 everywhere: s_A = s_B =
// s, Pr[X >= 1] = 1, and Eq. 3 = 0 because LB = 0 at the roots. A gap of 0.01: no overlap.
TEST(PairProbability, ShiftedFlatRootsByHand) {
  const DepthTree t(gen::makeFlatGrid(3.2, 1.6, 32, 16), exactCounting());
  const double ex = 2.0 * t.half(0).x();
  struct Shift {
    double dx;
    int s;
  };
  for (const Shift& shift : {Shift{0.5 * ex, 256}, Shift{ex - 0.05, 16}, Shift{ex, 16}}) {
    const Pose poseB{Mat3::Identity(), Vec3(shift.dx, 0.0, 0.0)};
    const detail::PairEstimate e = estimate(t, 0, Pose{}, t, 0, poseB);
    SCOPED_TRACE(testing::Message() << "shift " << shift.dx);
    ASSERT_TRUE(e.overlap);
    EXPECT_EQ(e.s, shift.s);
    EXPECT_EQ(e.sA, shift.s);
    EXPECT_EQ(e.sB, shift.s);
    EXPECT_DOUBLE_EQ(e.upper, 1.0);
    EXPECT_EQ(e.lower, 0.0);
  }
  const detail::PairEstimate apart =
      estimate(t, 0, Pose{}, t, 0, Pose{Mat3::Identity(), Vec3(ex + 0.01, 0.0, 0.0)});
  EXPECT_FALSE(apart.overlap);
  EXPECT_EQ(apart.s, 0);
  EXPECT_EQ(apart.lower, 0.0);
  EXPECT_EQ(apart.upper, 0.0);
  EXPECT_EQ(apart.expected, 0.0);
}

// Sparse nodes, where the balls-into-bins tail matters. A patch of stripPatches(1) (32 x 16
// cells of side 0.1, one column covered: density 1/32) against itself: s = 512, s_A = s_B =
// 16, E[X] = 16 * 16 / 512 = 0.5, Pr[X = 0] = prod_{i<16} (496 - i) / (512 - i). Against the
// patch of stripPatches(0.5) (side 0.05, also density 1/32) centred inside it: the common
// cell is 0.1, the small patch's box holds s = 16 x 8 = 128 of them, s_A = 128 / 32 = 4, and
// the small node's density doubles at the coarser cell (rho_C = rho h_C / h = 1/16): s_B = 8.
// Both nodes are at depth 1 of equally deep trees: LB = 2 / (2 dmax).
TEST(PairProbability, SparseStripsByHand) {
  const DepthTree big(stripPatches(1.0), exactCounting());
  const DepthTree small(stripPatches(0.5), exactCounting());
  const std::uint32_t pa = leftPatch(big), pb = leftPatch(small);
  // The premises: the depth-1 nodes are the patches, with the densities stated above.
  ASSERT_NEAR(2.0 * big.half(pa).x(), 3.2, 1e-5);
  ASSERT_NEAR(2.0 * big.half(pa).y(), 1.6, 1e-5);
  ASSERT_NEAR(2.0 * small.half(pb).x(), 1.6, 1e-5);
  ASSERT_EQ(big.depth[pa], 1);
  ASSERT_EQ(big.tree.maxDepth(), small.tree.maxDepth());
  ASSERT_FLOAT_EQ(big.tree.distributions()[pa].density, 1.0f / 32.0f);
  ASSERT_FLOAT_EQ(small.tree.distributions()[pb].density, 1.0f / 32.0f);
  const double lb = 1.0 / big.tree.maxDepth();

  // Eq. 3 from the closed-form tail.
  const auto eq3ByHand = [lb](int s, int sA, int sB) {
    return eq3(closedFormTail(s, sA, sB), sA, sB, lb);
  };

  std::mt19937_64 rng(test::kSeed);
  const Pose pose = randomPose(rng);
  const detail::PairEstimate same = estimate(big, pa, pose, big, pa, pose);
  ASSERT_TRUE(same.overlap);
  EXPECT_EQ(same.s, 512);
  EXPECT_EQ(same.sA, 16);
  EXPECT_EQ(same.sB, 16);
  double noCell = 1.0;
  for (int i = 0; i < 16; ++i) noCell *= (496.0 - i) / (512.0 - i);
  EXPECT_NEAR(same.upper, 1.0 - noCell, 1e-12);
  EXPECT_NEAR(same.lower, eq3ByHand(512, 16, 16), 1e-12);
  EXPECT_NEAR(same.expected, 0.5, 1e-6);

  const Pose poseB = placeB(big, pose, small, small.centre(pb), Mat3::Identity(),
                            big.centre(pa));
  const detail::PairEstimate nested = estimate(big, pa, pose, small, pb, poseB);
  ASSERT_TRUE(nested.overlap);
  EXPECT_EQ(nested.s, 128);
  EXPECT_EQ(nested.sA, 4);
  EXPECT_EQ(nested.sB, 8);
  noCell = 1.0;
  for (int i = 0; i < 8; ++i) noCell *= (124.0 - i) / (128.0 - i);
  EXPECT_NEAR(nested.upper, 1.0 - noCell, 1e-12);
  EXPECT_NEAR(nested.lower, eq3ByHand(128, 4, 8), 1e-12);
  EXPECT_NEAR(nested.expected, 128.0 / 32.0 / 16.0, 1e-6);
  // A sanity check of the hand tail itself: E[X] = sum_x Pr[X >= x] (X <= 4 here).
  const std::vector<double> tail = closedFormTail(128, 4, 8);
  EXPECT_NEAR(tail[1] + tail[2] + tail[3] + tail[4], 4.0 * 8.0 / 128.0, 1e-12);
}

// ---- Invariants over random pairs -------------------------------------------------------

// Over many random node pairs and poses (seeded): outputs are finite, 0 <= lower <= upper <=
// 1, expected >= 0, 1 <= s and 0 <= s_A, s_B <= s with the model's definition, p = 0 exactly
// when s_A or s_B is 0; boxes that one box's face axes separate give overlap == false with
// every estimate zero.
TEST(PairProbability, InvariantsOverRandomPairs) {
  std::mt19937_64 rng(test::kSeed + 1);
  const DepthTree* trees[] = {&torusTree(), &sphereTree(), &flatTree()};
  std::uniform_int_distribution<int> pickTree(0, 2);
  std::uniform_real_distribution<double> offset(-1.2, 1.2);
  int overlapping = 0, separated = 0, positive = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const DepthTree& a = *trees[pickTree(rng)];
    const DepthTree& b = *trees[pickTree(rng)];
    const auto pick = [&rng](const DepthTree& t) {
      return std::uniform_int_distribution<std::uint32_t>(
          0, static_cast<std::uint32_t>(t.tree.nodes().size() - 1))(rng);
    };
    const std::uint32_t ia = pick(a), ib = pick(b);
    const Mat3 rel = randomRotation(rng).toRotationMatrix();
    // b's centre within 1.2 times the sum of the half extents of a's centre, per axis.
    const Vec3 reach = a.half(ia) + rel.cwiseAbs() * b.half(ib);
    const Vec3 target =
        a.centre(ia) + Vec3(offset(rng), offset(rng), offset(rng)).cwiseProduct(reach);
    const Pose poseA = randomPose(rng);
    const Pose poseB = placeB(a, poseA, b, b.centre(ib), rel, target);
    const detail::PairEstimate e = estimate(a, ia, poseA, b, ib, poseB);
    SCOPED_TRACE(testing::Message() << "trial " << trial);

    ASSERT_TRUE(std::isfinite(e.lower) && std::isfinite(e.upper) && std::isfinite(e.expected));
    ASSERT_GE(e.lower, 0.0);
    ASSERT_LE(e.lower, e.upper);
    ASSERT_LE(e.upper, 1.0);
    ASSERT_GE(e.expected, 0.0);

    // Separated along a face axis of A (or of B) by more than rounding: never overlapping.
    const auto apart = [](const Node& n, const Aabb& other) {
      const double margin = 1e-9 * (1.0 + other.extent().norm());
      for (int k = 0; k < 3; ++k) {
        if (other.lo[k] > n.hi[k] + margin || other.hi[k] < n.lo[k] - margin) return true;
      }
      return false;
    };
    if (apart(a.tree.nodes()[ia], mappedBox(b, poseB, ib, a, poseA)) ||
        apart(b.tree.nodes()[ib], mappedBox(a, poseA, ia, b, poseB))) {
      ASSERT_FALSE(e.overlap);
      ++separated;
    }
    if (!e.overlap) {
      ASSERT_EQ(e.lower, 0.0);
      ASSERT_EQ(e.upper, 0.0);
      ASSERT_EQ(e.expected, 0.0);
      ASSERT_EQ(e.s + e.sA + e.sB, 0);
      continue;
    }
    ++overlapping;
    ASSERT_GE(e.s, 1);
    ASSERT_LE(e.s, kMaxBins);
    ASSERT_TRUE(e.sA >= 0 && e.sA <= e.s && e.sB >= 0 && e.sB <= e.s);
    expectCountsMatchTheModel(e, cellModel(a, ia, poseA, b, ib, poseB));
    if (e.sA == 0 || e.sB == 0) {
      ASSERT_EQ(e.upper, 0.0);
      ASSERT_EQ(e.lower, 0.0);
    } else {
      ASSERT_GT(e.upper, 0.0);
      ++positive;
    }
  }
  // Every branch is exercised (1275, 2330 and 1235 of 4000 when written).
  EXPECT_GE(overlapping, 1000);
  EXPECT_GE(separated, 1500);
  EXPECT_GE(positive, 800);
}

// The overlap test is conservative: two nodes holding triangles that really cross (placed so
// that a triangle of each shares its centroid, random relative rotation) always overlap, get
// at least one common cell, and a positive Pr[X >= 1] whenever both have possible collision
// cells.
TEST(PairProbability, NodesWithCrossingTrianglesAlwaysOverlap) {
  std::mt19937_64 rng(test::kSeed + 2);
  const DepthTree* trees[] = {&torusTree(), &sphereTree(), &flatTree()};
  std::uniform_int_distribution<int> pickTree(0, 2);
  int crossing = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const DepthTree& a = *trees[pickTree(rng)];
    const DepthTree& b = *trees[pickTree(rng)];
    // A random node, and a random triangle below it (walk down to a random leaf).
    const auto pick = [&rng](const DepthTree& t, std::uint32_t& node, std::uint32_t& tri) {
      const int d = std::uniform_int_distribution<int>(0, t.tree.maxDepth())(rng);
      const auto& level = t.byDepth[std::min<std::size_t>(d, t.byDepth.size() - 1)];
      node = level[std::uniform_int_distribution<std::size_t>(0, level.size() - 1)(rng)];
      std::uint32_t leaf = node;
      while (!t.tree.nodes()[leaf].isLeaf()) {
        leaf = t.tree.nodes()[leaf].firstChild() + static_cast<std::uint32_t>(rng() & 1u);
      }
      const Node& l = t.tree.nodes()[leaf];
      tri = l.firstTriangle() + static_cast<std::uint32_t>(rng() % l.triangleCount());
    };
    std::uint32_t ia = 0, ta = 0, ib = 0, tb = 0;
    pick(a, ia, ta);
    pick(b, ib, tb);
    const auto corners = [](const DepthTree& t, std::uint32_t tri) {
      const Triangle& idx = t.tree.triangles()[tri];
      return std::array<Vec3, 3>{t.tree.localVertices()[idx[0]],
                                 t.tree.localVertices()[idx[1]],
                                 t.tree.localVertices()[idx[2]]};
    };
    const auto va = corners(a, ta), vb = corners(b, tb);
    const Mat3 rel = randomRotation(rng).toRotationMatrix();
    const Pose poseA = randomPose(rng);
    const Pose poseB = placeB(a, poseA, b, (vb[0] + vb[1] + vb[2]) / 3.0, rel,
                              (va[0] + va[1] + va[2]) / 3.0);
    // b's triangle in A's local frame.
    std::array<Vec3, 3> vbInA;
    for (int k = 0; k < 3; ++k) {
      const Vec3 world = poseB.rotation * (vb[k] + b.tree.origin()) + poseB.translation;
      vbInA[k] = poseA.rotation.transpose() * (world - poseA.translation) - a.tree.origin();
    }
    if (!trianglesIntersect(va[0], va[1], va[2], vbInA[0], vbInA[1], vbInA[2])) continue;
    ++crossing;
    const detail::PairEstimate e = estimate(a, ia, poseA, b, ib, poseB);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " nodes " << ia << " " << ib);
    ASSERT_TRUE(e.overlap);
    ASSERT_GE(e.s, 1);
    if (e.sA > 0 && e.sB > 0) {
      ASSERT_GT(e.upper, 0.0);
    }
  }
  EXPECT_GE(crossing, 900);  // two triangles through one common point (all when written)
}

}  // namespace
}  // namespace adb
