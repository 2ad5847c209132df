// Internal: a pair the scheduler noted during Bullet's dispatch, with its scheduling state,
// and Bullet's wrappers rebuilt from it.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <LinearMath/btTransform.h>

#include <cstdint>

#include "adb/core/query.h"

namespace adb {
class ManifoldAlgorithm;
class MeshMeshAlgorithm;
}

namespace adb::detail {

/// A pair noted during the dispatch: enough to rebuild Bullet's wrappers and result
/// afterwards (the dispatch's own live on its stack; a compound's child wrappers only
/// during its call), and the pair's scheduling state.
struct DeferredPair {
  ManifoldAlgorithm* algorithm;
  const btCollisionObject* object0;
  const btCollisionObject* object1;
  const btCollisionShape* shape0;  // the wrapper's shape: a compound's child for a child pair
  const btCollisionShape* shape1;
  btTransform transform0, transform1;  // the wrappers' world transforms, kept by value
  int partId0, index0, partId1, index1;
  std::uint32_t sequence;  // order of the dispatch: ties in the whole pairs' order
  // A whole pair: how far its mesh moved against the other body since it last ran (its
  // kept contacts' error), infinite if it never ran. The most moved run first.
  btScalar motion = 0;
  // A whole pair: FrameScheduler::urgency(), worked out once per step before the pairs are
  // sorted (it re-measures kept contacts): 0 arriving, 1 losing its hold or approaching (both
  // run whatever the budget), 2 the others.
  std::uint8_t urgency = 2;
  // Scheduling state of this step.
  std::uint64_t grant = 0;     // node pairs granted this step (all its queries)
  double confidence = 0.0;     // see FrameStats::meanConfidence
  double completeness = 0.0;   // see FrameStats::meanCompleteness: the refinement's order
  StopReason stop = StopReason::Completed;
  // Its contacts are in its manifold. Set before the first pass only for a pair that kept
  // them (FrameScheduler::keepRestingContacts): such a pair waits for nothing this step.
  bool written = false;
  bool resting = false;        // a whole pair left out of the first pass: its mesh barely moved
  bool overdue = false;        // a mesh-mesh pair: FrameScheduler::overdue() at the step's start
  // A whole pair whose contacts were gathered on the pool this step: its index in the
  // scheduler's gathered contacts; -1 otherwise.
  std::int32_t gathered = -1;

  /// Completed, stopped on quality or with its contacts found: nothing left to refine.
  bool decided() const { return !isBudgetStop(stop); }
  /// The mesh-mesh algorithm of a refinable pair.
  MeshMeshAlgorithm& meshMesh() const;
};

/// Bullet's wrappers of a deferred pair, rebuilt as the dispatch made them.
struct PairWrappers {
  btCollisionObjectWrapper body0, body1;
  explicit PairWrappers(const DeferredPair& pair);
};

}  // namespace adb::detail
