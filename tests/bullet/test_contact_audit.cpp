// The contact audit (FrameSettings::auditContacts): its verdict on every plausible contact is
// brute force's over the triangles below the contact's two nodes, its counts agree with what
// the step wrote, and it leaves the simulation as it was, to the bit.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "adb/core/triangle_distance.h"
#include "adb/core/triangle_test.h"
#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// A knot dropped into a torus lying flat, overlapping it from the first step, under a budget
// far below what the pair needs (about 200 node pairs for exact contacts): the pair is cut
// every step it touches. Small meshes (256 and about 400 triangles) keep the brute force
// below cheap.
constexpr std::uint64_t kBudget = 24;
constexpr int kSteps = 20;

FrameSettings auditSettings(bool audit) {
  FrameSettings f;
  f.budgetNodePairs = kBudget;
  // Every open pair is accepted (the most probable 8), whatever the probability's fitted
  // weights: the audit then has contacts to judge.
  f.pAccept = 0.0;
  f.auditContacts = audit;
  return f;
}

void addKnotInTorus(World& w) {
  const TriangleMesh torus = gen::transformed(
      gen::makeTorus(0.4, 0.15, 16, 8),
      Pose{Eigen::AngleAxisd(test::kQuarterTurn, Vec3::UnitX()).toRotationMatrix(),
           Vec3::Zero()});
  w.add(MeshData::build(torus), 0, btVector3(0, 0, 0));
  btRigidBody* knot =
      w.add(MeshData::build(gen::makeModel("knot", 400)), 1, btVector3(btScalar(0.3), btScalar(0.2), 0));
  knot->setActivationState(DISABLE_DEACTIVATION);
}

// Brute force over every triangle below node a of tree A and node b of tree B, posed as the
// contact was made: whether some pair intersects or lies within `reach`.
bool trianglesWithin(const AuditedContact& c, double reach) {
  const auto below = [](const AdbTree& tree, std::uint32_t node, std::vector<std::uint32_t>& out) {
    std::vector<std::uint32_t> stack{node};
    while (!stack.empty()) {
      const Node& n = tree.nodes()[stack.back()];
      stack.pop_back();
      if (n.isLeaf()) {
        for (std::uint32_t t = 0; t < n.triangleCount(); ++t) out.push_back(n.firstTriangle() + t);
      } else {
        stack.push_back(n.firstChild());
        stack.push_back(n.firstChild() + 1);
      }
    }
  };
  const auto corners = [](const AdbTree& tree, const Pose& pose, std::uint32_t t, Vec3 v[3]) {
    for (int k = 0; k < 3; ++k) {
      v[k] = pose.apply(tree.localVertices()[tree.triangles()[t][k]] + tree.origin());
    }
  };
  std::vector<std::uint32_t> ta, tb;
  below(*c.treeA, c.nodeA, ta);
  below(*c.treeB, c.nodeB, tb);
  for (std::uint32_t i : ta) {
    Vec3 a[3];
    corners(*c.treeA, c.poseA, i, a);
    for (std::uint32_t j : tb) {
      Vec3 b[3];
      corners(*c.treeB, c.poseB, j, b);
      if (trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2])) return true;
      if (triangleDistance(a[0], a[1], a[2], b[0], b[1], b[2]).distance <= reach) return true;
    }
  }
  return false;
}

TEST(ContactAudit, EveryVerdictIsBruteForcesAndTheCountsAddUp) {
  World w(test::Dispatch::Adb, auditSettings(true));
  addKnotInTorus(w);
  std::vector<AuditedContact> contacts;
  std::uint64_t audited = 0, ghosts = 0, exact = 0;
  for (int step = 0; step < kSteps; ++step) {
    w.step();
    const FrameStats& s = w.adbDispatcher->lastFrameStats();
    const ContactAuditStats& a = s.audit;
    ASSERT_TRUE(a.on);
    // The audited pairs are the cut ones, and it judged the plausible contacts they wrote.
    EXPECT_EQ(a.pairs, s.cutPairs + s.qualityPairs);
    EXPECT_EQ(a.accepted, s.plausibleContacts);
    EXPECT_LE(a.farGhosts, a.ghosts);
    EXPECT_LE(a.ghosts, a.accepted);
    EXPECT_LE(a.missedOpen, a.missed);
    EXPECT_LE(a.missed, a.exact);
    EXPECT_EQ(a.cappedPairs, 0u) << "a few hundred triangles cannot fill the exact query's list";
    w.adbDispatcher->lastAuditedContacts(contacts);
    ASSERT_EQ(contacts.size(), a.accepted);
    std::uint32_t stepGhosts = 0, stepFarGhosts = 0;
    for (const AuditedContact& c : contacts) {
      EXPECT_EQ(c.ghost, !trianglesWithin(c, c.margin))
          << "step " << step << ", nodes " << c.nodeA << " and " << c.nodeB;
      EXPECT_EQ(c.farGhost, !trianglesWithin(c, c.threshold))
          << "step " << step << ", nodes " << c.nodeA << " and " << c.nodeB;
      EXPECT_GE(c.threshold, c.margin);
      stepGhosts += c.ghost ? 1 : 0;
      stepFarGhosts += c.farGhost ? 1 : 0;
    }
    EXPECT_EQ(stepGhosts, a.ghosts);
    EXPECT_EQ(stepFarGhosts, a.farGhosts);
    audited += a.accepted;
    ghosts += a.ghosts;
    exact += a.exact;
  }
  // Else the test judged nothing: the budget must cut the pair and leave contacts to judge.
  EXPECT_GT(audited, 0u);
  EXPECT_GT(exact, 0u);
  EXPECT_GT(ghosts, 0u) << "every open pair accepted: some lie apart";
  EXPECT_LT(ghosts, audited) << "every open pair accepted: some touch";
}

TEST(ContactAudit, LeavesTheSimulationBitIdentical) {
  const auto run = [](bool audit) {
    World w(test::Dispatch::Adb, auditSettings(audit));
    addKnotInTorus(w);
    std::vector<std::uint64_t> hashes;
    std::uint32_t cut = 0;
    for (int step = 0; step < kSteps; ++step) {
      w.step();
      const FrameStats& s = w.adbDispatcher->lastFrameStats();
      EXPECT_EQ(s.audit.on, audit);
      cut += s.cutPairs;
      hashes.push_back(test::hashBodies(w.bodies));
    }
    EXPECT_GT(cut, 0u) << "the budget must cut the pair for the audit to run";
    return hashes;
  };
  EXPECT_EQ(run(false), run(true));
}

TEST(ContactAudit, OffByDefaultAndListsNothing) {
  World w(test::Dispatch::Adb, auditSettings(false));
  addKnotInTorus(w);
  w.step();
  EXPECT_FALSE(w.adbDispatcher->lastFrameStats().audit.on);
  std::vector<AuditedContact> contacts(3);
  w.adbDispatcher->lastAuditedContacts(contacts);
  EXPECT_TRUE(contacts.empty());
  EXPECT_FALSE(FrameSettings{}.auditContacts);
}

}  // namespace
}  // namespace adb
