// Internal: the few contact points worth handing to a manifold, chosen from many candidates.
//
// A mesh lying on a floor offers hundreds of candidate points (every vertex near a plane,
// every triangle near a box). Bullet's manifold keeps 4, and fed one point at a time it
// keeps whichever arrived in a good order: fed in tree order, it could hold 4 shallow points
// while the deepest went unseen, and bodies sank. Here the deepest point is always kept;
// then, among the points about as deep as it (the support: a vertex hovering within the
// breaking distance is not touching), those nearest the manifold's points from the last step
// (so that Bullet matches them and warm-starts their impulses: new points every step leave a
// resting body jittering), then the ones that span the widest support. Only those reach the
// manifold. Fixed capacity: no allocation per step.
#pragma once

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <cstdint>

#include "adb/bullet/precision.h"

namespace adb::detail {

/// Contacts of a mesh with a box or a plane: the tree is cut into 2^kContactRegionLevel
/// regions, each giving its deepest contacts (adb::forEachDeepestTriangleNear): a manifold
/// keeps 4 points, and 16 candidates spread over the mesh leave it the choice. Regions at
/// level 4 give resting bodies their support (docs/bullet-results.md); a node or triangle
/// that cannot reach deeper than its region's best is not tested (no slack: ties, a flat
/// face on a floor, are skipped either way).
inline constexpr int kContactRegionLevel = 4;
/// Under a budget too small for every pair, 2^kCoarseRegionLevel regions: the deepest points
/// of each quarter of the tree, still the 4 a manifold keeps, for about a quarter of the
/// work (FrameScheduler::runWhole).
inline constexpr int kCoarseRegionLevel = 2;

/// One candidate, in Bullet's terms for the result's body order.
struct CandidateContact {
  btVector3 normalOnB;  ///< unit, on body 1, pointing towards body 0
  btVector3 pointOnB;   ///< world point on body 1
  btScalar distance;    ///< < 0 penetrating
  int meshTriangle;     ///< the mesh's triangle index (Bullet's shape identifier)
};

class ContactSelection {
 public:
  /// Candidates kept at most: past this, a deeper candidate replaces the shallowest.
  static constexpr int kCapacity = 256;
  /// Points written to the manifold per step at most: the 4 it holds (a fifth would make it
  /// drop one of the others every step).
  static constexpr int kWritten = 4;

  void add(const CandidateContact& c);
  /// Empties it for another step (a selection kept by the scheduler is reused).
  void clear() { m_count = 0; }
  int size() const { return m_count; }
  /// The closest candidate (the deepest), or nullptr when there is none.
  const CandidateContact* closest() const;
  /// Writes the deepest candidate; then, among those within a quarter of the breaking
  /// threshold of its depth, the ones nearest the points `previous` (the pair's manifold,
  /// before this step's points) holds, within the breaking threshold; then greedily the ones
  /// farthest from those already written (the widest support).
  /// `meshIsBody0` picks which shape identifier the triangle index goes to. Returns the
  /// number of points written.
  int write(btManifoldResult& result, bool meshIsBody0, const btPersistentManifold& previous);

 private:
  CandidateContact m_candidates[kCapacity];
  int m_count = 0;
};

}  // namespace adb::detail
