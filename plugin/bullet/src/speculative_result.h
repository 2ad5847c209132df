// Internal: SpeculativeResult, a btManifoldResult that also keeps contacts farther apart than
// the manifold's breaking threshold (speculative contacts of a fast body, up to the distance
// the bodies can close in the step) in a second manifold of the pair.
//
// Why a second manifold: Bullet's manifold matches a new point to a kept one when their
// points on body A lie within its breaking threshold of each other. Raising the threshold to
// the speculative reach (half a metre for a gear at 30 m/s) merged every new point into one,
// and the gear pivoted about it through a 2 cm wall. Bullet's own speculative contacts for
// convex bodies (btDiscreteDynamicsWorld::createPredictiveContacts) take the same route: a
// manifold of their own, cleared every step, filled without matching.
#pragma once

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

namespace adb::detail {

class SpeculativeResult : public btManifoldResult {
 public:
  /// `base`'s bodies, part ids and manifold; points beyond its manifold's breaking threshold
  /// and within `reach` go to `speculative` (none when it is null).
  SpeculativeResult(const btManifoldResult& base, btPersistentManifold* speculative,
                    btScalar reach)
      : btManifoldResult(base), m_speculative(speculative), m_reach(reach) {}
  /// A new result for the two bodies, as btManifoldResult(body0, body1).
  SpeculativeResult(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                    btPersistentManifold* speculative, btScalar reach)
      : btManifoldResult(body0, body1), m_speculative(speculative), m_reach(reach) {}

  void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld,
                       btScalar depth) override;

 private:
  btPersistentManifold* m_speculative;
  btScalar m_reach;
};

}  // namespace adb::detail
