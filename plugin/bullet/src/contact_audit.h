// Internal: the audit of a step's plausible contacts (FrameSettings::auditContacts). Each
// mesh-mesh pair that got plausible contacts is judged against its triangles at the poses
// its contacts were made for:
//  - ghosts: accepted plausible contacts whose two nodes' triangles do not come within the
//    pair's contact margin of each other (brute force over the triangles below both nodes);
//  - missed: triangle pairs an exact query of the pair finds that the cut query neither
//    found nor covered by an accepted plausible contact.
// It reads the pair's trees and its query's evidence and writes only its own buffers and the
// statistics: the world is untouched.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/geometry.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "pair_contacts.h"

class btCollisionObject;

namespace adb::detail {

/// How near the triangles below two posed nodes come to each other.
struct NodeProximity {
  bool withinMargin = false;  ///< some pair intersects or lies within the margin
  bool withinReach = false;   ///< some pair lies within the reach (>= the margin)
};

class ContactAudit {
 public:
  /// One pair that got plausible contacts, and its query's evidence.
  struct PairEvidence {
    PosedPair posed;
    const std::vector<Witness>* found = nullptr;  ///< the cut query's witnesses
    const std::vector<OpenPair>* open = nullptr;  ///< the node pairs it left unresolved
    double margin = 0.0;     ///< the pair's contact margin (MeshMeshAlgorithm::contactMargin)
    double threshold = 0.0;  ///< max(margin, the manifold's breaking threshold)
    const btCollisionObject* body0 = nullptr;
    const btCollisionObject* body1 = nullptr;
  };

  /// Audits one pair: adds to `stats` and appends a verdict per accepted plausible contact
  /// (selectPlausible with `settings`, as the pair's contacts were chosen) to `contacts`.
  void audit(const PairEvidence& pair, const FrameSettings& settings, ContactAuditStats& stats,
             std::vector<AuditedContact>& contacts);

  /// Brute force over the triangles below node `a` of tree A and node `b` of tree B, posed:
  /// whether some pair intersects or lies within `margin`, and within `reach`.
  NodeProximity proximity(const PosedPair& posed, std::uint32_t a, std::uint32_t b,
                          double margin, double reach);

 private:
  // A triangle in world coordinates with its box.
  struct WorldTriangle {
    Vec3 v[3];
    Vec3 lo, hi;
  };
  // The triangles below `node`, posed, into `out`; returns their box.
  static void poseTriangles(const AdbTree& tree, const Pose& pose, std::uint32_t node,
                            std::vector<WorldTriangle>& out, Vec3& lo, Vec3& hi);

  Traversal m_exact;  // the exact query, reused (grows to the largest pair, then stays)
  std::vector<WorldTriangle> m_a, m_b;
  std::vector<std::uint64_t> m_found;  // the cut query's triangle pairs, sorted
  // Per open pair: the triangles below its two nodes (first A, end A, first B, end B).
  std::vector<std::array<std::uint32_t, 4>> m_openRanges;
};

}  // namespace adb::detail
