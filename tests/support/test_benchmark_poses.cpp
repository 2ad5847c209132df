// Tests of the benchmark poses for two different meshes (plugin/support/src/benchmark_poses.cpp):
// the pair's unit, Zachmann's poses of a pair (each mesh about its own centre, the one-mesh
// poses when both boxes are one), and the robot-in-a-room poses.
#include <gtest/gtest.h>

#include <random>

#include "adb/support/benchmark_poses.h"

namespace adb {
namespace {

const Aabb kA{Vec3(-3, -2, -1), Vec3(3, 2, 1)};        // unit 3
const Aabb kB{Vec3(0.1, 0.2, 0.3), Vec3(0.5, 0.4, 1.3)};  // unit 0.5, off the origin

TEST(PairPoses, UnitIsTheMeanOfTheTwoUnits) {
  EXPECT_DOUBLE_EQ(benchmarkUnit(kA, kB), 1.75);
  EXPECT_EQ(benchmarkUnit(kB, kB), benchmarkUnit(kB));  // exactly, not nearly
}

TEST(PairPoses, OneBoxTwiceGivesTheOneMeshPosesBitForBit) {
  std::mt19937_64 one(4), two(4);
  for (int i = 0; i < 50; ++i) {
    const PosePair p = benchmarkPoses(kB, 0.1 * i, one);
    const PosePair q = benchmarkPoses(kB, kB, 0.1 * i, two);
    EXPECT_EQ(p.a.rotation, q.a.rotation);
    EXPECT_EQ(p.a.translation, q.a.translation);
    EXPECT_EQ(p.b.rotation, q.b.rotation);
    EXPECT_EQ(p.b.translation, q.b.translation);
  }
}

TEST(PairPoses, CentresAreDistancePairUnitsApartAlongX) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 50; ++i) {
    const double d = 0.05 * i;
    const PosePair p = benchmarkPoses(kA, kB, d, rng);
    // Each mesh turns about its own box centre: A's stays at the origin, B's lands on x.
    EXPECT_LT(p.a.apply(kA.center()).norm(), 1e-12);
    EXPECT_LT((p.b.apply(kB.center()) - Vec3(d * 1.75, 0, 0)).norm(), 1e-12) << d;
  }
}

TEST(InsidePoses, AStaysAtTheIdentityAndBsCentreFillsAsBox) {
  std::mt19937_64 rng(6);
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    const PosePair p = insidePoses(kA, kB, rng);
    EXPECT_EQ(p.a.rotation, Mat3::Identity());
    EXPECT_EQ(p.a.translation, Vec3::Zero());
    EXPECT_LT((p.b.rotation.transpose() * p.b.rotation - Mat3::Identity()).norm(), 1e-12);
    const Vec3 c = p.b.apply(kB.center());
    EXPECT_TRUE((c.array() >= kA.lo.array() - 1e-12).all() &&
                (c.array() <= kA.hi.array() + 1e-12).all())
        << c.transpose();
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  // Uniform: 2,000 centres come within 2 % of the box's every face.
  EXPECT_TRUE(((lo - kA.lo).array() < 0.02 * kA.extent().array()).all()) << lo.transpose();
  EXPECT_TRUE(((kA.hi - hi).array() < 0.02 * kA.extent().array()).all()) << hi.transpose();
}

}  // namespace
}  // namespace adb
