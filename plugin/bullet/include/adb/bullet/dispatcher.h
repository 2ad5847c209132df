// adb::Dispatcher: a btCollisionDispatcher that registers adb's algorithms and spends one
// per-step budget across every pair that involves an adb mesh (adb/bullet/frame_budget.h).
//
// Bullet dispatches pairs one after another, so a budget spent inside each algorithm would
// go first come, first served. Here adb's algorithms only note their pair while Bullet
// dispatches: mesh-mesh, mesh against a convex shape, a plane or another concave shape, and
// meshes inside compounds. When the dispatch is over, the scheduler spends the step's budget
// (pairs with a static body first, then where the uncertainty is largest) and writes every
// pair's manifold, before the solver runs. contactTest/contactPairTest are answered at once
// and exactly, outside the budget.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include <functional>
#include <memory>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/bullet/precision.h"
#include "adb/bullet/registration.h"

namespace adb {

class ManifoldAlgorithm;
namespace detail {
class FrameScheduler;  // opaque: the plugin's own
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
  /// Statistics of the last step's adb pairs.
  const FrameStats& lastFrameStats() const;
  /// The last step's mesh-mesh pairs, into `out` (cleared first; reuse it across steps and
  /// nothing is allocated once it is large enough). A pair inside a compound names the
  /// compound's body.
  void lastMeshPairs(std::vector<MeshPairReport>& out) const;
  /// With FrameSettings::auditContacts, the last step's accepted plausible contacts as the
  /// audit judged them, into `out` (cleared first; empty with the audit off): which were
  /// ghosts, with their node pairs and poses to check them by.
  void lastAuditedContacts(std::vector<AuditedContact>& out) const;

  /// Called once per step for each body whose pose adb cannot use (NaN, a rotation that is
  /// not orthonormal beyond btScalar's rounding, beyond 1e150) or whose velocities are not
  /// finite, as soon as one of its adb pairs meets it. The body's adb pairs are skipped and
  /// their manifolds emptied, so that the solver carries no NaN to the bodies it touches;
  /// lastFrameStats() names the body too. The callback must not throw: an exception from it
  /// is swallowed (none may leave Bullet's step).
  void setBadPoseCallback(std::function<void(const BadPose&)> callback);

  void dispatchAllCollisionPairs(btOverlappingPairCache* pairCache,
                                 const btDispatcherInfo& info, btDispatcher* dispatcher) override;

 private:
  friend class ManifoldAlgorithm;  // hands its pairs to the scheduler

  FrameSettings m_settings;
  std::unique_ptr<detail::FrameScheduler> m_scheduler;
};

}  // namespace adb
