// adb::Dispatcher: a btCollisionDispatcher that registers adb's algorithms and spends a
// per-step budget across all mesh-mesh pairs of the step (adb/bullet/frame_budget.h).
//
// Bullet dispatches pairs one after another, so a budget spent inside each algorithm would
// go first come, first served. Here the mesh-mesh algorithms only note their pair while
// Bullet dispatches; when the dispatch is over, the scheduler spends the step's budget where
// the uncertainty is largest and writes every pair's manifold, before the solver runs.
// Other pairs (mesh-plane, mesh-convex, ...) are processed by Bullet's dispatch as usual.
// contactTest/contactPairTest, and mesh pairs inside compounds, are answered immediately and
// exactly, outside the budget.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include <functional>
#include <memory>

#include "adb/bullet/frame_budget.h"
#include "adb/bullet/mesh_mesh_algorithm.h"  // collisionConstructionInfo(), registration
#include "adb/bullet/precision.h"

namespace adb {

namespace detail {
class FrameScheduler;
}

class Dispatcher : public btCollisionDispatcher {
 public:
  /// Registers adb's algorithms on itself (adb::registerAlgorithms): `configuration` must
  /// have been made from adb::collisionConstructionInfo() (throws SettingsError otherwise).
  explicit Dispatcher(btDefaultCollisionConfiguration* configuration);
  ~Dispatcher() override;

  /// Throws SettingsError naming the first invalid field (NaN or negative budget, pMin or
  /// pAccept outside [0, 1], kMin < 0, maxPlausibleContacts < 0, softCfm < 0 or NaN).
  void setFrameSettings(const FrameSettings& settings);
  const FrameSettings& frameSettings() const { return m_settings; }
  /// Statistics of the last step's mesh-mesh pairs.
  const FrameStats& lastFrameStats() const;

  /// Called once per step for each body whose pose adb cannot use (NaN, a rotation that is
  /// not orthonormal, beyond 1e150), as soon as one of its adb pairs meets it. The body's
  /// adb pairs are skipped and their manifolds emptied, so that the solver carries no NaN
  /// to the bodies it touches; lastFrameStats() names the body too. The callback must not
  /// throw: an exception from it is swallowed (none may leave Bullet's step).
  void setBadPoseCallback(std::function<void(const BadPose&)> callback);
  /// Internal: an adb algorithm met `body` with an unusable pose.
  void reportBadPose(const btCollisionObject* body, PoseDefect defect);

  void dispatchAllCollisionPairs(btOverlappingPairCache* pairCache,
                                 const btDispatcherInfo& info, btDispatcher* dispatcher) override;

  /// Internal: the scheduler mesh-mesh algorithms hand their pair to during a dispatch.
  detail::FrameScheduler& scheduler() { return *m_scheduler; }

 private:
  FrameSettings m_settings;
  std::unique_ptr<detail::FrameScheduler> m_scheduler;
  std::function<void(const BadPose&)> m_badPoseCallback;
};

}  // namespace adb
