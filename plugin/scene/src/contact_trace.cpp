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

// Every body pair's points, its manifolds together (adb's speculative one, a compound's one
// per child pair, GImpact's per part).
ContactTrace::Pairs ContactTrace::pairsOf(btDispatcher& dispatcher) {
  Pairs pairs;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold& manifold = *dispatcher.getManifoldByIndexInternal(m);
    if (manifold.getNumContacts() == 0) continue;
    PairPoints& pair = pairs[PairKey{manifold.getBody0(), manifold.getBody1()}];
    pair.threshold =
        std::max(pair.threshold, static_cast<double>(manifold.getContactBreakingThreshold()));
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      const btManifoldPoint& p = manifold.getContactPoint(i);
      Point point{p.m_index0, p.m_index1, {}, {}, {}};
      store(p.m_positionWorldOnA, point.onA);
      store(p.m_positionWorldOnB, point.onB);
      store(p.m_normalWorldOnB, point.normal);
      pair.points.push_back(point);
    }
  }
  return pairs;
}

// Each point matched to last step's by its features, else (points without features) as Bullet
// matches them: the nearest unclaimed one within the breaking threshold.
ContactChurn ContactTrace::compare(const PairPoints& now, const PairPoints* before) const {
  ContactChurn c;
  const std::size_t count = before ? before->points.size() : 0;
  std::vector<bool> claimed(count, false);
  for (const Point& p : now.points) {
    ++c.points;
    int match = -1;
    bool byId = false;
    for (std::size_t k = 0; k < count && hasFeatures(p.index0, p.index1); ++k) {
      const Point& old = before->points[k];
      if (!claimed[k] && old.index0 == p.index0 && old.index1 == p.index1) {
        match = static_cast<int>(k);
        byId = true;
        break;
      }
    }
    double best = now.threshold;
    for (std::size_t k = 0; k < count && !byId; ++k) {
      const double d = distance(before->points[k].onB, p.onB);
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
    const Point& old = before->points[static_cast<std::size_t>(match)];
    ++c.matched;
    c.keptId += byId ? 1 : 0;
    c.moved += distance(old.onA, p.onA) > m_moved || distance(old.onB, p.onB) > m_moved ? 1 : 0;
    const double cosine =
        old.normal[0] * p.normal[0] + old.normal[1] * p.normal[1] + old.normal[2] * p.normal[2];
    c.turned += cosine < m_turnedCos ? 1 : 0;
  }
  for (bool k : claimed) c.dropped += k ? 0 : 1;
  return c;
}

// Bodies whose deactivation timer went back: Bullet found them over their thresholds.
int ContactTrace::writeResets(btDiscreteDynamicsWorld& dynamics, int step,
                              std::map<const void*, BodyChurn>& bodies, int& awake) {
  int resets = 0;
  awake = 0;
  const btCollisionObjectArray& objects = dynamics.getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) {
    const btRigidBody* body = btRigidBody::upcast(objects[i]);
    if (!body || body->getInvMass() == 0) continue;
    const bool asleep = body->getActivationState() == ISLAND_SLEEPING;
    awake += asleep ? 0 : 1;
    const double timer = static_cast<double>(body->getDeactivationTime());
    double& last = m_timers[body];
    const bool reset = timer < last && !asleep;
    last = timer;
    if (!reset) continue;
    ++resets;
    const BodyChurn& b = bodies[body];
    m_resetsFile << step << ',' << body->getUserIndex() << ','
                 << body->getLinearVelocity().length() << ','
                 << body->getAngularVelocity().length() << ',' << b.pairs << ','
                 << b.churn.points << ',' << b.churn.keptId << ',' << b.churn.fresh << ','
                 << b.churn.moved << ',' << b.churn.turned << ',' << b.churn.dropped << '\n';
  }
  return resets;
}

void ContactTrace::record(SceneWorld& world) {
  btDiscreteDynamicsWorld* dynamics = world.dynamicsWorld();
  if (!dynamics) return;
  Pairs now = pairsOf(*dynamics->getDispatcher());
  std::map<const void*, BodyChurn> bodies;
  ContactChurn churn;
  const auto add = [&](const PairKey& key, const ContactChurn& c, bool held) {
    churn.add(c);
    for (const void* body : {key.first, key.second}) {
      bodies[body].churn.add(c);
      bodies[body].pairs += held ? 1 : 0;
    }
  };
  for (const auto& [key, pair] : now) {
    const auto before = m_last.find(key);
    add(key, compare(pair, before == m_last.end() ? nullptr : &before->second), true);
  }
  // Pairs that held points last step and none now dropped them all.
  for (const auto& [key, pair] : m_last) {
    if (now.count(key)) continue;
    ContactChurn c;
    c.dropped = static_cast<std::uint32_t>(pair.points.size());
    add(key, c, false);
  }
  const int step = world.last().step;
  int awake = 0;
  const int resets = writeResets(*dynamics, step, bodies, awake);
  m_resets += static_cast<std::uint64_t>(resets);
  m_total.add(churn);
  m_churn << step << ',' << now.size() << ',' << churn.points << ',' << churn.keptId << ','
          << churn.matched << ',' << churn.fresh << ',' << churn.moved << ',' << churn.turned
          << ',' << churn.dropped << ',' << resets << ',' << awake << '\n';
  m_last = std::move(now);
}

}  // namespace adb::scene
