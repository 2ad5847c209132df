// ContactTrace: manifolds compared step to step, and the bodies whose deactivation timer reset.
#include "adb/scene/contact_trace.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adb::scene {
namespace {

double distance(const double a[3], const double b[3]) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool hasFeatures(int index0, int index1) { return index0 != -1 || index1 != -1; }

void store(const btVector3& v, double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<double>(v[i]);
}

}  // namespace

void ContactChurn::add(const ContactChurn& o) {
  points += o.points;
  keptId += o.keptId;
  matched += o.matched;
  fresh += o.fresh;
  moved += o.moved;
  turned += o.turned;
  dropped += o.dropped;
}

ContactTrace::ContactTrace(const std::filesystem::path& folder, double movedOver,
                           double turnedOverDegrees)
    : m_moved(movedOver), m_turnedCos(std::cos(turnedOverDegrees * M_PI / 180.0)) {
  std::filesystem::create_directories(folder);
  m_churn.open(folder / "contact_churn.csv");
  m_resetsFile.open(folder / "sleep_resets.csv");
  if (!m_churn || !m_resetsFile) {
    throw std::runtime_error("contact trace: cannot write in " + folder.string());
  }
  m_churn << "step,pairs,points,kept_id,matched,new,moved,turned,dropped,resets,awake\n";
  m_resetsFile << "step,body,speed,spin,pairs,points,kept_id,new,moved,turned,dropped\n";
}

void ContactTrace::record(SceneWorld& world) {
  btDiscreteDynamicsWorld* dynamics = world.dynamicsWorld();
  if (!dynamics) return;
  const int step = world.last().step;
  btDispatcher& dispatcher = *dynamics->getDispatcher();
  // Every pair's points, its manifolds together (adb's speculative one, a compound's one per
  // child pair, GImpact's per part), and the largest breaking threshold among them.
  std::map<PairKey, std::vector<Point>> now;
  std::map<PairKey, double> thresholds;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    if (manifold.getNumContacts() == 0) continue;
    const PairKey key{manifold.getBody0(), manifold.getBody1()};
    std::vector<Point>& points = now[key];
    double& threshold = thresholds[key];
    threshold = std::max(threshold, static_cast<double>(manifold.getContactBreakingThreshold()));
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      const btManifoldPoint& p = manifold.getContactPoint(i);
      Point point{p.m_index0, p.m_index1, {}, {}, {}};
      store(p.m_positionWorldOnA, point.onA);
      store(p.m_positionWorldOnB, point.onB);
      store(p.m_normalWorldOnB, point.normal);
      points.push_back(point);
    }
  }
  std::map<const void*, ContactChurn> perBody;
  std::map<const void*, int> manifoldsOf;
  ContactChurn churn;
  int manifolds = 0;
  for (const auto& [key, points] : now) {
    const std::vector<Point>* before = nullptr;
    if (auto it = m_last.find(key); it != m_last.end()) before = &it->second;
    std::vector<bool> claimed(before ? before->size() : 0, false);
    ContactChurn c;
    for (const Point& p : points) {
      ++c.points;
      int match = -1;
      bool byId = false;
      for (std::size_t k = 0; before && k < before->size() && hasFeatures(p.index0, p.index1); ++k) {
        const Point& old = (*before)[k];
        if (!claimed[k] && old.index0 == p.index0 && old.index1 == p.index1) {
          match = static_cast<int>(k);
          byId = true;
          break;
        }
      }
      double best = thresholds[key];
      for (std::size_t k = 0; before && k < before->size() && match < 0; ++k) {
        const double d = distance((*before)[k].onB, p.onB);
        if (!claimed[k] && d < best) {
          best = d;
          match = static_cast<int>(k);
        }
      }
      if (match < 0) {
        ++c.fresh;
        continue;
      }
      claimed[static_cast<std::size_t>(match)] = true;
      const Point& old = (*before)[static_cast<std::size_t>(match)];
      ++c.matched;
      c.keptId += byId ? 1 : 0;
      c.moved += distance(old.onA, p.onA) > m_moved || distance(old.onB, p.onB) > m_moved ? 1 : 0;
      const double cosine = old.normal[0] * p.normal[0] + old.normal[1] * p.normal[1] +
                            old.normal[2] * p.normal[2];
      c.turned += cosine < m_turnedCos ? 1 : 0;
    }
    for (bool k : claimed) c.dropped += k ? 0 : 1;
    ++manifolds;
    churn.add(c);
    for (const void* body : {key.first, key.second}) {
      perBody[body].add(c);
      ++manifoldsOf[body];
    }
  }
  // Manifolds that held points last step and none now dropped them all.
  for (const auto& [key, points] : m_last) {
    if (now.count(key)) continue;
    ContactChurn c;
    c.dropped = static_cast<std::uint32_t>(points.size());
    churn.add(c);
    perBody[key.first].add(c);
    perBody[key.second].add(c);
  }
  // Bodies whose deactivation timer went back: Bullet found them over their thresholds.
  int resets = 0, awake = 0;
  const btCollisionObjectArray& objects = dynamics->getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btRigidBody* body = btRigidBody::upcast(objects[i]);
    if (!body || body->getInvMass() == 0) continue;
    awake += body->getActivationState() == ISLAND_SLEEPING ? 0 : 1;
    const double timer = static_cast<double>(body->getDeactivationTime());
    double& last = m_timers[body];
    const bool reset = timer < last && body->getActivationState() != ISLAND_SLEEPING;
    last = timer;
    if (!reset) continue;
    ++resets;
    const ContactChurn& c = perBody[body];
    m_resetsFile << step << ',' << body->getUserIndex() << ','
                 << body->getLinearVelocity().length() << ','
                 << body->getAngularVelocity().length() << ',' << manifoldsOf[body] << ','
                 << c.points << ',' << c.keptId << ',' << c.fresh << ',' << c.moved << ','
                 << c.turned << ',' << c.dropped << '\n';
  }
  m_resets += static_cast<std::uint64_t>(resets);
  m_total.add(churn);
  m_churn << step << ',' << manifolds << ',' << churn.points << ',' << churn.keptId << ','
          << churn.matched << ',' << churn.fresh << ',' << churn.moved << ',' << churn.turned
          << ',' << churn.dropped << ',' << resets << ',' << awake << '\n';
  m_last = std::move(now);
}

}  // namespace adb::scene
