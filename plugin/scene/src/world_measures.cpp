#include "world_measures.h"

#include <algorithm>

namespace adb::scene::detail {
namespace {

// Bodies slower than this are at rest (m/s and rad/s).
constexpr double kRestSpeed = 0.05;

std::uint32_t indexOf(const btCollisionObject* o) {
  return static_cast<std::uint32_t>(o->getUserIndex());
}

const MeshPairReport* reportOf(const std::vector<MeshPairReport>& reports,
                               const btCollisionObject* a, const btCollisionObject* b) {
  for (const MeshPairReport& r : reports) {
    if ((r.body0 == a && r.body1 == b) || (r.body0 == b && r.body1 == a)) return &r;
  }
  return nullptr;
}

}  // namespace

void measureContacts(const btCollisionDispatcher& dispatcher, const Dispatcher* adb,
                     std::vector<MeshPairReport>& reports, StepRecord& record,
                     std::vector<ContactPoint>& contacts, std::vector<CutPair>& cutPairs) {
  contacts.clear();
  cutPairs.clear();
  reports.clear();
  if (adb) {
    adb->lastMeshPairs(reports);
    record.frame = adb->lastFrameStats();
    record.meshPairs = record.frame.pairs;
    record.cutPairs = record.frame.cutPairs;
    record.meanConfidence = record.frame.meanConfidence;
    record.worstConfidence = record.frame.worstConfidence;
  }
  for (const MeshPairReport& r : reports) {
    if (r.outcome == MeshPairReport::Outcome::Cut) {
      cutPairs.push_back(CutPair{indexOf(r.body0), indexOf(r.body1), r.confidence});
    }
  }
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold =
        dispatcher.getManifoldByIndexInternal(m);
    const MeshPairReport* report = reportOf(reports, manifold->getBody0(), manifold->getBody1());
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& point = manifold->getContactPoint(p);
      const btVector3& at = point.getPositionWorldOnB();
      ContactPoint c;
      c.position = Vec3(at.x(), at.y(), at.z());
      c.depth = std::max(0.0, -static_cast<double>(point.getDistance()));
      c.confidence = report ? report->confidence : 1.0;
      c.body0 = indexOf(manifold->getBody0());
      c.body1 = indexOf(manifold->getBody1());
      contacts.push_back(c);
      record.penetration = std::max(record.penetration, c.depth);
    }
  }
  record.contacts = static_cast<std::uint32_t>(contacts.size());
}

void measureDynamics(const btDiscreteDynamicsWorld& world, const Vec3& gravity,
                     StepRecord& record) {
  const btCollisionObjectArray& objects = world.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btRigidBody* body = btRigidBody::upcast(objects[i]);
    if (!body || body->getInvMass() == 0) continue;
    const double mass = 1.0 / body->getInvMass();
    const btVector3 v = body->getLinearVelocity();
    const btVector3 w = body->getAngularVelocity();
    // Rotational energy: w . (I_world w) / 2, with I_world = R diag(I) R^T.
    const btMatrix3x3& r = body->getWorldTransform().getBasis();
    const btVector3 local = r.transpose() * w;
    const btVector3 inertia = body->getLocalInertia();
    const double rotational = 0.5 * (inertia.x() * local.x() * local.x() +
                                     inertia.y() * local.y() * local.y() +
                                     inertia.z() * local.z() * local.z());
    const double kinetic = 0.5 * mass * v.length2() + rotational;
    const btVector3& x = body->getWorldTransform().getOrigin();
    const double potential = -mass * (gravity.x() * x.x() + gravity.y() * x.y() + gravity.z() * x.z());
    record.kinetic += kinetic;
    record.energy += kinetic + potential;
    record.atRest += v.length() < kRestSpeed && w.length() < kRestSpeed ? 1 : 0;
    record.asleep += body->getActivationState() == ISLAND_SLEEPING ? 1 : 0;
  }
}

}  // namespace adb::scene::detail
