// Hard cases, one named test each: degenerate triangles, flat meshes, single triangles,
// touching and coplanar faces, far from the origin, tiny and huge scales, zero and huge
// budgets, bad query settings. Exact mode must match the brute-force oracle; ADB mode must stay
// finite, in range and sensible.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "test_support.h"

namespace adb {
namespace {

void expectSane(const QueryResult& r) {
  EXPECT_TRUE(r.confidence >= 0.0 && r.confidence <= 1.0) << r.confidence;
  EXPECT_TRUE(std::isfinite(r.seconds));
}

Pose at(const Vec3& t) { return Pose{Mat3::Identity(), t}; }

// Exact mode vs the oracle over random benchmark poses; ADB results must be sane.
void checkAgainstOracle(const TriangleMesh& a, const TriangleMesh& b, int poses,
                        double maxDistance = 2.0) {
  AdbTree ta(a), tb(b);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  Aabb both = a.bounds();
  both.grow(b.bounds());
  for (int i = 0; i < poses; ++i) {
    const double d = maxDistance * (i + 0.5) / poses;
    const PosePair p = benchmarkPoses(both, d, rng);
    const bool truth = test::bruteForceCollide(a, p.a, b, p.b);
    const QueryResult e = collide(ta, p.a, tb, p.b, test::exactSettings(), scratch);
    ASSERT_EQ(e.collides, truth) << "pose " << i << " distance " << d;
    expectSane(collide(ta, p.a, tb, p.b, test::adbSettings(), scratch));
  }
}

TEST(HardCaseDegenerate, DegenerateTrianglesAreHandledEverywhere) {
  // A torus with extra degenerate triangles: repeated indices, collinear vertices, and
  // distinct vertices at one position.
  const TriangleMesh torus = gen::makeTorus(1.0, 0.3, 16, 8);
  std::vector<Vec3> v = torus.vertices();
  std::vector<Triangle> t = torus.triangles();
  const auto n = static_cast<std::uint32_t>(v.size());
  v.push_back(v[0]);                               // a duplicate position
  v.push_back(0.5 * (v[0] + v[1]));                // the midpoint of an edge: collinear
  for (std::uint32_t i = 0; i + 2 < n; i += 7) t.push_back({i, i, i + 1});
  t.push_back({0, n, 1});
  t.push_back({0, 1, n + 1});
  t.push_back({n, n, n});
  const TriangleMesh mesh(v, t, "degenerate torus");
  ASSERT_GT(mesh.report().degenerateTriangles, 10u);
  const AdbTree tree(mesh);
  for (const Node& node : tree.nodes()) ASSERT_TRUE(std::isfinite(node.pc) && node.pc >= 0.0f);
  checkAgainstOracle(mesh, mesh, 40);
}

TEST(HardCaseDegenerate, MeshOfOnlyDegenerateTriangles) {
  // Zero total area: every count is zero, queries still answer exactly.
  const TriangleMesh segments({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}},
                              {{0, 1, 2}, {0, 0, 3}, {3, 3, 3}}, "segments");
  const AdbTree tree(segments);
  for (const Node& node : tree.nodes()) EXPECT_EQ(node.pc, 0.0f);
  const TriangleMesh tri({{0.5, -1, -1}, {0.5, 1, -1}, {0.5, 0, 1}}, {{0, 1, 2}});
  const AdbTree crossing(tri);
  QueryScratch scratch;
  // The x-axis segment pierces the triangle in the plane x = 0.5.
  EXPECT_TRUE(collide(tree, Pose{}, crossing, Pose{}, test::exactSettings(), scratch).collides);
  EXPECT_FALSE(
      collide(tree, Pose{}, crossing, at(Vec3(0, 0, 5)), test::exactSettings(), scratch).collides);
}

TEST(HardCaseFlat, FlatMeshesGiveFiniteCountsAndExactAnswers) {
  const TriangleMesh flat = gen::makeFlatGrid(2.0, 2.0, 16, 16);
  for (CellCounting counting : {CellCounting::Approximate, CellCounting::Exact}) {
    BuildSettings s;
    s.counting = counting;
    const AdbTree tree(flat, s);
    // A fully covered flat square: one layer of 23 x 23 flat cells (node_geometry.h), all
    // possible collision cells; the approximate count (area / h^2) lands on the same number.
    EXPECT_NEAR(tree.root().pc, 529.0f, counting == CellCounting::Exact ? 0.0f : 529.0f * 0.05f);
    EXPECT_NEAR(tree.distributions()[0].density, 1.0f, 0.05f);
    for (const Node& node : tree.nodes()) ASSERT_TRUE(std::isfinite(node.pc));
  }
  checkAgainstOracle(flat, flat, 40);
  checkAgainstOracle(flat, gen::makeTorus(0.8, 0.25, 16, 8), 40);
}

TEST(HardCaseFlat, CoplanarParallelAndCrossingSheets) {
  const TriangleMesh flat = gen::makeFlatGrid(2.0, 2.0, 8, 8);
  const AdbTree tree(flat);
  QueryScratch scratch;
  const auto exact = [&](const Pose& pb) {
    return collide(tree, Pose{}, tree, pb, test::exactSettings(), scratch).collides;
  };
  EXPECT_TRUE(exact(at(Vec3(0.5, 0.25, 0))));   // coplanar, overlapping
  EXPECT_TRUE(exact(at(Vec3(2.0, 0, 0))));      // coplanar, sharing an edge
  EXPECT_FALSE(exact(at(Vec3(2.0 + 1e-9, 0, 0))));
  EXPECT_FALSE(exact(at(Vec3(0, 0, 1e-9))));    // parallel, a hair apart
  const Pose upright{Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()};
  EXPECT_TRUE(exact(upright));                  // crossing at right angles
  // ADB must find the crossing sheets too (the padding of flat nodes, node_geometry.h).
  const QueryResult r = collide(tree, Pose{}, tree, upright, test::adbSettings(), scratch);
  expectSane(r);
  EXPECT_TRUE(r.collides);
}

TEST(HardCaseSingleTriangle, SingleTriangleMeshes) {
  const TriangleMesh a({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}});
  const TriangleMesh b({{0, -0.5, -1}, {0, -0.5, 1}, {0, 0.5, 0}}, {{0, 1, 2}});
  const AdbTree ta(a), tb(b);
  QueryScratch scratch;
  for (const QuerySettings& s : {test::exactSettings(), test::adbSettings()}) {
    const QueryResult hit = collide(ta, Pose{}, tb, Pose{}, s, scratch);
    EXPECT_TRUE(hit.collides);
    EXPECT_EQ(hit.confidence, 1.0);  // two leaves: decided by the exact test in both modes
    const QueryResult miss = collide(ta, Pose{}, tb, at(Vec3(0, 0, 2.5)), s, scratch);
    EXPECT_FALSE(miss.collides);
    EXPECT_EQ(miss.confidence, 1.0);
  }
}

TEST(HardCaseTouching, BoxesFaceToFace) {
  const TriangleMesh box = gen::makeBox(Vec3(0.5, 0.5, 0.5), 2);
  const AdbTree tree(box);
  QueryScratch scratch;
  const auto exact = [&](const Pose& pb) {
    return collide(tree, Pose{}, tree, pb, test::exactSettings(), scratch).collides;
  };
  // What counts as a collision: closed triangles sharing a point (triangle_test.h). Faces
  // that touch collide; a gap of 1e-9 (far above the 1e-12 relative tolerance) does not.
  EXPECT_TRUE(exact(at(Vec3(1.0, 0, 0))));             // coplanar faces, fully overlapping
  EXPECT_TRUE(exact(at(Vec3(1.0, 0.5, 0.25))));        // coplanar faces, partly overlapping
  EXPECT_TRUE(exact(at(Vec3(1.0, 1.0, 1.0))));         // corner on corner
  EXPECT_FALSE(exact(at(Vec3(1.0 + 1e-9, 0, 0))));
  EXPECT_FALSE(exact(at(Vec3(1.0, 1.0 + 1e-9, 1.0))));
  // Edge on face: B rotated 45 degrees about z rests an edge on A's top face.
  const Pose edge{Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX()).toRotationMatrix(),
                  Vec3(0, 0, 0.5 + 0.5 * std::sqrt(2.0))};
  EXPECT_TRUE(exact(edge));
  EXPECT_FALSE(exact(Pose{edge.rotation, edge.translation + Vec3(0, 0, 1e-9)}));
}

TEST(HardCaseFarFromOrigin, SameAnswersAt1e5) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 20, 10);
  const Vec3 far(1e5, -2e5, 1e5);
  const TriangleMesh moved = gen::transformed(mesh, Pose{Mat3::Identity(), far});
  const AdbTree near(mesh), away(moved);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  int adbSame = 0, total = 0;
  for (double d = 0.3; d <= 2.0; d += 0.1) {
    for (int i = 0; i < 8; ++i) {
      const PosePair p = benchmarkPoses(mesh.bounds(), d, rng);
      // The moved mesh's file coordinates are shifted by `far`: undo it in the pose, then put
      // the pair 1e5 away from the world origin too.
      const Pose qa{p.a.rotation, p.a.translation - p.a.rotation * far + far};
      const Pose qb{p.b.rotation, p.b.translation - p.b.rotation * far + far};
      const bool truth = test::bruteForceCollide(mesh, p.a, mesh, p.b);
      EXPECT_EQ(collide(away, qa, away, qb, test::exactSettings(), scratch).collides, truth);
      const QueryResult rn = collide(near, p.a, near, p.b, test::adbSettings(), scratch);
      const QueryResult rf = collide(away, qa, away, qb, test::adbSettings(), scratch);
      adbSame += rn.collides == rf.collides ? 1 : 0;
      ++total;
    }
  }
  // Local frames make the ADB traversal see the same numbers up to rounding of the shift.
  EXPECT_GE(adbSame, total - 1);
}

TEST(HardCaseScale, TinyAndHugeScalesGiveTheSameAnswers) {
  const TriangleMesh unit = gen::makeTorusKnot(2, 3, 1.0, 0.25, 48, 6);
  const AdbTree unitTree(unit);
  QueryScratch scratch;
  for (double scale : {1e-3, 1e3}) {
    std::vector<Vec3> v = unit.vertices();
    for (Vec3& x : v) x *= scale;
    const TriangleMesh scaled(v, unit.triangles(), "scaled");
    const AdbTree tree(scaled);
    std::mt19937_64 rng(test::kSeed), rngScaled(test::kSeed);
    int adbSame = 0, total = 0;
    for (double d = 0.3; d <= 2.0; d += 0.1) {
      for (int i = 0; i < 6; ++i) {
        const PosePair p = benchmarkPoses(unit.bounds(), d, rng);
        const PosePair ps = benchmarkPoses(scaled.bounds(), d, rngScaled);
        const bool truth = test::bruteForceCollide(unit, p.a, unit, p.b);
        EXPECT_EQ(collide(tree, ps.a, tree, ps.b, test::exactSettings(), scratch).collides,
                  truth)
            << "scale " << scale << " d " << d;
        const QueryResult r1 = collide(unitTree, p.a, unitTree, p.b, test::adbSettings(), scratch);
        const QueryResult rs = collide(tree, ps.a, tree, ps.b, test::adbSettings(), scratch);
        expectSane(rs);
        adbSame += r1.collides == rs.collides ? 1 : 0;
        ++total;
      }
    }
    // The model is scale-free (volume ratios, depths); only rounding of s may differ.
    EXPECT_GE(adbSame, total - 2) << "scale " << scale;
  }
}

TEST(HardCaseScale, MeshesOutsideTheFloatRangeAreRejected) {
  const TriangleMesh unit = gen::makeTorus(1.0, 0.3, 12, 6);
  for (double scale : {1e-14, 1e14, 1e39}) {
    std::vector<Vec3> v = unit.vertices();
    for (Vec3& x : v) x *= scale;
    const TriangleMesh scaled(v, unit.triangles(), "scaled torus");
    try {
      AdbTree tree(scaled);
      FAIL() << "scale " << scale;
    } catch (const MeshError& e) {
      EXPECT_NE(std::string(e.what()).find("scaled torus"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("rescale"), std::string::npos);
    }
  }
  // The ends of the supported range still answer exactly.
  for (double scale : {1e-9, 1e9}) {
    std::vector<Vec3> v = unit.vertices();
    for (Vec3& x : v) x *= scale;
    const TriangleMesh scaled(v, unit.triangles());
    const AdbTree tree(scaled);
    QueryScratch scratch;
    const Pose near{Mat3::Identity(), Vec3(1.0 * scale, 0, 0)};
    const Pose far{Mat3::Identity(), Vec3(3.0 * scale, 0, 0)};
    EXPECT_TRUE(collide(tree, Pose{}, tree, near, test::exactSettings(), scratch).collides);
    EXPECT_FALSE(collide(tree, Pose{}, tree, far, test::exactSettings(), scratch).collides);
  }
}

// The MeshError message of building a tree over `mesh`, or "" when the build succeeds.
std::string buildError(const TriangleMesh& mesh, const BuildSettings& settings = {}) {
  try {
    AdbTree tree(mesh, settings);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

// Three copies of one point, one triangle: a mesh of extent 0.
TriangleMesh pointMesh(const Vec3& p, const std::string& name = "point") {
  return TriangleMesh({p, p, p}, {{0, 1, 2}}, name);
}

void expectFiniteBoxes(const AdbTree& tree) {
  ASSERT_TRUE(tree.origin().allFinite());
  for (const Node& n : tree.nodes()) {
    ASSERT_TRUE(n.boxLo().allFinite() && n.boxHi().allFinite() && std::isfinite(n.pc));
  }
  for (const NodeDistribution& d : tree.distributions()) {
    ASSERT_TRUE(std::isfinite(d.offset) && std::isfinite(d.halfWidth) && std::isfinite(d.side));
  }
}

TEST(HardCaseRange, PointMeshNearDoubleMaxIsRejected) {
  // The fuzz case: one repeated point near 9e307 has extent 0, which skipped the extent check;
  // its box centre (lo + hi) / 2 overflowed to inf, so the tree held inf boxes and a NaN
  // centre. Coordinates beyond the supported magnitude are now refused with a MeshError that
  // names the mesh, the vertex and the range.
  for (const Vec3& p : {Vec3(9e307, 9e307, 9e307), Vec3(-9e307, -9e307, -9e307),
                        Vec3(9e307, -9e307, 1.0), Vec3(1e151, 0, 0)}) {
    const std::string e = buildError(pointMesh(p, "far point"));
    EXPECT_NE(e.find("far point: vertex 0 is at"), std::string::npos) << e;
    EXPECT_NE(e.find("1e+150"), std::string::npos) << e;
  }
}

TEST(HardCaseRange, SpreadPointsNearDoubleMaxAreRejected) {
  // Distinct points near +-9e307: their extent is huge or overflows to inf (hi - lo across
  // the origin). Either way the message names the out-of-range coordinates, not "inf units".
  const auto mesh = [](double a, double b, double c) {
    return TriangleMesh({{a, b, c}, {b, c, a}, {c, a, b}}, {{0, 1, 2}}, "spread");
  };
  for (const TriangleMesh& m : {mesh(9e307, 8.9e307, 8.8e307), mesh(-9e307, -8.9e307, -8.8e307),
                                mesh(9e307, -9e307, 0.0)}) {
    const std::string e = buildError(m);
    EXPECT_NE(e.find("spread: vertex 0 is at"), std::string::npos) << e;
    EXPECT_NE(e.find("1e+150"), std::string::npos) << e;
    EXPECT_EQ(e.find("inf"), std::string::npos) << e;
  }
}

TEST(HardCaseRange, FlatMeshFarAlongOneAxisIsRejected) {
  // A unit triangle in the plane x = 1e200 passes the extent check (1 unit across) and its
  // tree has finite boxes, but a query squares the distance between tree origins (1e400):
  // the same magnitude rule refuses it.
  const TriangleMesh far({{1e200, 0, 0}, {1e200, 1, 0}, {1e200, 0, 1}}, {{0, 1, 2}}, "plane");
  const std::string e = buildError(far);
  EXPECT_NE(e.find("plane: vertex 0 is at (1e+200, 0, 0)"), std::string::npos) << e;
}

TEST(HardCaseRange, PointMeshAtOrdinaryPlaceStillWorks) {
  // Extent 0 at an ordinary place (and at the largest supported magnitude) stays legal: the
  // tree is one point at the local origin and exact queries agree with the oracle.
  for (const Vec3& p : {Vec3(1, 2, 3), Vec3(1e150, -1e150, 1e150)}) {
    const TriangleMesh point = pointMesh(p);
    const AdbTree tree(point);
    expectFiniteBoxes(tree);
    EXPECT_EQ(tree.origin(), p);
    EXPECT_EQ(tree.root().boxLo(), Vec3::Zero());
    EXPECT_EQ(tree.root().boxHi(), Vec3::Zero());
  }
  const TriangleMesh point = pointMesh(Vec3(1, 2, 3));
  const TriangleMesh tri({{1, 0, 0}, {1, 4, 0}, {1, 0, 6}}, {{0, 1, 2}});  // plane x = 1
  const AdbTree tp(point), tt(tri);
  QueryScratch scratch;
  for (const Vec3& t : {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0, 5, 5)}) {
    const bool truth = test::bruteForceCollide(point, Pose{}, tri, at(t));
    EXPECT_EQ(collide(tp, Pose{}, tt, at(t), test::exactSettings(), scratch).collides, truth)
        << t.transpose();
    expectSane(collide(tp, Pose{}, tt, at(t), test::adbSettings(), scratch));
  }
}

TEST(HardCaseRange, SmallMeshFarFromOriginStillWorks) {
  // A mesh 1e18 from the origin but 1e6 across is legitimate: finite boxes, exact answers.
  const TriangleMesh unit = gen::makeTorus(1.0, 0.3, 16, 8);
  std::vector<Vec3> v = unit.vertices();
  for (Vec3& x : v) x = 1e6 * x + Vec3(1e18, -1e18, 1e18);
  const TriangleMesh far(v, unit.triangles(), "far torus");
  const AdbTree tree(far);
  expectFiniteBoxes(tree);
  QueryScratch scratch;
  for (double dx : {0.5e6, 1.0e6, 1.5e6, 3.0e6}) {
    const bool truth = test::bruteForceCollide(far, Pose{}, far, at(Vec3(dx, 0, 0)));
    EXPECT_EQ(truth, dx < 2.6e6) << dx;  // the torus is 2.6e6 across
    EXPECT_EQ(collide(tree, Pose{}, tree, at(Vec3(dx, 0, 0)), test::exactSettings(), scratch)
                  .collides,
              truth)
        << dx;
  }
}

TEST(HardCaseMessages, SmallAndLargeNumbersPrintReadably) {
  // Numbers in error messages are printed with %g (std::to_string printed 1e-15 as
  // "0.000000"), with more digits only where 6 would not tell the value from the limit.
  const auto triangle = [](double s) {
    return TriangleMesh({{0, 0, 0}, {s, 0, 0}, {0, s, 0}}, {{0, 1, 2}}, "tiny");
  };
  EXPECT_NE(buildError(triangle(1e-15)).find("tiny: the mesh is 1e-15 units across"),
            std::string::npos)
      << buildError(triangle(1e-15));
  EXPECT_NE(buildError(triangle(2.5e13)).find("2.5e+13 units across"), std::string::npos);
  const TriangleMesh mesh = gen::makeSphere(1.0, 1);
  const auto settingsError = [&](double threshold) -> std::string {
    BuildSettings s;
    s.areaThreshold = threshold;
    try {
      AdbTree tree(mesh, s);
    } catch (const SettingsError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(settingsError(-1e-9).find("areaThreshold is -1e-09;"), std::string::npos)
      << settingsError(-1e-9);
  EXPECT_NE(settingsError(1.0000001).find("areaThreshold is 1.0000001;"), std::string::npos)
      << settingsError(1.0000001);
}

TEST(HardCaseBudget, ZeroBudgetsAreValid) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 40, 20);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  const PosePair p = benchmarkPoses(mesh.bounds(), 0.8, rng);
  QuerySettings s = test::adbSettings();
  s.budgetMicros = 0.0;
  const QueryResult timed = collide(tree, p.a, tree, p.b, s, scratch);
  expectSane(timed);
  EXPECT_EQ(timed.stop, StopReason::TimeBudget);
  s = test::adbSettings();
  s.budgetNodePairs = 0;
  const QueryResult work = collide(tree, p.a, tree, p.b, s, scratch);
  expectSane(work);
  EXPECT_EQ(work.stop, StopReason::WorkBudget);
  EXPECT_LE(work.nodePairs, 1u);  // the roots' own test
  // Nothing was explored: the answer is the estimate's from the roots alone, never near
  // certain.
  EXPECT_LT(work.confidence, 0.95);
  // Separated roots need no budget at all.
  const QueryResult apart =
      collide(tree, Pose{}, tree, at(Vec3(10, 0, 0)), s, scratch);
  EXPECT_FALSE(apart.collides);
  EXPECT_EQ(apart.confidence, 1.0);
}

TEST(HardCaseBudget, HugeBudgetsEqualNoBudget) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 40, 20);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  for (int i = 0; i < 20; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.5 + 0.1 * i, rng);
    QuerySettings s = test::adbSettings();
    const QueryResult free = collide(tree, p.a, tree, p.b, s, scratch);
    s.budgetMicros = 1e12;
    s.budgetNodePairs = std::numeric_limits<std::uint64_t>::max() - 1;
    const QueryResult big = collide(tree, p.a, tree, p.b, s, scratch);
    EXPECT_EQ(free.collides, big.collides);
    EXPECT_EQ(free.confidence, big.confidence);
    EXPECT_EQ(free.nodePairs, big.nodePairs);
  }
}

TEST(HardCaseTouching, NearlyOrthonormalRotationsKeepExactAnswers) {
  // B's rotation is orthonormal only to ~1e-6 (accepted: the pose tolerance is 1e-6): a turn
  // about x, scaled by 1 + 4.9e-7. B sits beside A's +x face, overlapping or apart by 1e-7 to
  // 5e-7. The frame uses true inverses (a transpose would misplace A in B's frame by ~1e-6),
  // so exact mode agrees with the oracle applying the same matrices.
  const TriangleMesh box = gen::makeBox(Vec3(0.5, 0.5, 0.5), 8);
  const AdbTree tree(box);
  QueryScratch scratch;
  constexpr double kScale = 1.0 + 4.9e-7;
  int collisions = 0;
  for (int i = 0; i < 100; ++i) {
    const Mat3 r = Eigen::AngleAxisd(0.01 * i, Vec3::UnitX()).toRotationMatrix() * kScale;
    const double gap = (i % 2 == 0 ? -1e-7 : 1e-7) * (1 + i % 5);  // < 0: overlap
    const Pose pb{r, Vec3(0.5 + 0.5 * kScale + gap, 0.1, -0.2)};
    const bool truth = test::bruteForceCollide(box, Pose{}, box, pb);
    collisions += truth ? 1 : 0;
    EXPECT_EQ(collide(tree, Pose{}, tree, pb, test::exactSettings(), scratch).collides, truth)
        << "pose " << i << " gap " << gap;
  }
  EXPECT_EQ(collisions, 50);  // the overlapping half
}

TEST(HardCaseBadInput, NonFiniteOrSkewedPosesAreRejected) {
  const TriangleMesh mesh = gen::makeSphere(1.0, 1);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  const auto message = [&](const Pose& pb) -> std::string {
    try {
      collide(tree, Pose{}, tree, pb, test::adbSettings(), scratch);
    } catch (const PoseError& e) {
      return e.what();
    }
    return "";
  };
  Pose p;
  p.translation.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(p).find("pose B has a non-finite entry"), std::string::npos);
  p = Pose{};
  p.rotation(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(p).find("non-finite"), std::string::npos);
  p = Pose{};
  p.rotation *= 2.0;  // a scale is not a rotation
  EXPECT_NE(message(p).find("not orthonormal"), std::string::npos);
  // Off orthonormal by about 2.4e-6: the message shows the number, not "0.000002".
  p = Pose{};
  p.rotation(0, 0) += 1.2e-6;
  EXPECT_NE(message(p).find("= 2.4"), std::string::npos) << message(p);
  EXPECT_NE(message(p).find("e-06)"), std::string::npos) << message(p);
  // Beyond 1e150 the distance between tree origins overflows when squared and the query
  // would cull nothing: refused, with the number.
  p = Pose{};
  p.translation.x() = 1e160;
  EXPECT_NE(message(p).find("translation of 1e+160"), std::string::npos) << message(p);
  p.translation.x() = 1e149;  // far, but supported
  EXPECT_EQ(message(p), "");
  // A rotation built from a quaternion in double is orthonormal to rounding: accepted.
  EXPECT_EQ(message(Pose::fromQuaternion(Eigen::Quaterniond(0.3, 0.1, -0.7, 0.2), Vec3(1, 2, 3))),
            "");
}

TEST(HardCaseBadInput, InvalidQuerySettingsAreRejectedWithTheirName) {
  const TriangleMesh mesh = gen::makeSphere(1.0, 1);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  const auto message = [&](QuerySettings s) -> std::string {
    try {
      collide(tree, Pose{}, tree, Pose{}, s, scratch);
    } catch (const SettingsError& e) {
      return e.what();
    }
    return "";
  };
  QuerySettings s;
  s.pMin = std::nan("");
  EXPECT_NE(message(s).find("pMin"), std::string::npos);
  s = QuerySettings{};
  s.pMin = 1.5;
  EXPECT_NE(message(s).find("pMin"), std::string::npos);
  s = QuerySettings{};
  s.kMin = 0;
  EXPECT_NE(message(s).find("kMin"), std::string::npos);
  s = QuerySettings{};
  s.budgetMicros = -1.0;
  EXPECT_NE(message(s).find("budgetMicros"), std::string::npos);
  s = QuerySettings{};
  s.budgetMicros = std::nan("");
  EXPECT_NE(message(s).find("budgetMicros"), std::string::npos);
}

}  // namespace
}  // namespace adb
