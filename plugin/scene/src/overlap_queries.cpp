#include "overlap_queries.h"

#include <algorithm>
#include <limits>

#include "adb/bullet/conversions.h"

namespace adb::scene::detail {
namespace {

// Bullet's own pair test: any point with a negative distance is an overlap.
struct AnyPenetration : btCollisionWorld::ContactResultCallback {
  bool hit = false;
  btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper*, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    if (point.getDistance() < 0) hit = true;
    return 0;
  }
};

std::uint32_t indexOf(const btCollisionObject& o) { return static_cast<std::uint32_t>(o.getUserIndex()); }

}  // namespace

OverlapQueries::OverlapQueries(const Scene& scene, Backend backend) : m_budget(scene.world.budget) {
  // The paper's traversal when the scene sets a quality target; otherwise the exact descent,
  // which under a budget answers "no" when cut before a hit (with its confidence).
  const bool quality = backend == Backend::Adb && scene.world.kMin > 0;
  m_settings.mode = quality ? QueryMode::Adb : QueryMode::Exact;
  m_settings.pMin = scene.world.pMin;
  m_settings.kMin = std::max(1, scene.world.kMin);
  m_settings.stopAtFirstHit = true;
  m_budgeted = backend == Backend::Adb && m_budget.kind != BudgetSpec::Kind::None;
  m_adbQueries = usesAdbShapes(backend);
}

PairAnswer OverlapQueries::meshPair(const btCollisionObject& a, const btCollisionObject& b,
                                    const MeshData& ma, const MeshData& mb,
                                    std::size_t meshPairsLeft) {
  QuerySettings settings = m_settings;
  if (m_budgeted) {
    const double share = 1.0 / static_cast<double>(std::max<std::size_t>(meshPairsLeft, 1));
    if (m_budget.kind == BudgetSpec::Kind::Micros) {
      settings.budgetMicros = std::max(0.0, m_microsLeft * share);
    } else {
      settings.budgetNodePairs = static_cast<std::uint64_t>(static_cast<double>(m_nodePairsLeft) * share);
    }
  }
  const QueryResult r =
      collide(ma.tree, toPose(a.getWorldTransform()), mb.tree, toPose(b.getWorldTransform()),
              settings, m_scratch);
  m_microsLeft -= r.seconds * 1e6;
  m_nodePairsLeft -= std::min(m_nodePairsLeft, r.nodePairs);
  PairAnswer answer;
  answer.overlap = r.collides;
  answer.confidence = r.confidence;
  answer.meshMesh = true;
  answer.cut = isBudgetStop(r.stop);
  return answer;
}

PairAnswer OverlapQueries::bulletPair(btCollisionWorld& world, btCollisionObject& a,
                                      btCollisionObject& b) {
  AnyPenetration test;
  world.contactPairTest(&a, &b, test);
  PairAnswer answer;
  answer.overlap = test.hit;
  return answer;
}

void OverlapQueries::run(btCollisionWorld& world,
                         const std::vector<std::shared_ptr<const MeshData>>& meshes,
                         StepRecord& record) {
  m_answers.clear();
  m_pairs.clear();
  btBroadphasePairArray& pairs = world.getPairCache()->getOverlappingPairArray();
  std::size_t meshPairs = 0;
  for (int i = 0; i < pairs.size(); ++i) {
    auto* a = static_cast<btCollisionObject*>(pairs[i].m_pProxy0->m_clientObject);
    auto* b = static_cast<btCollisionObject*>(pairs[i].m_pProxy1->m_clientObject);
    if (indexOf(*b) < indexOf(*a)) std::swap(a, b);
    m_pairs.emplace_back(a, b);
    if (m_adbQueries && meshes[indexOf(*a)] && meshes[indexOf(*b)]) ++meshPairs;
  }
  // The broadphase's order is its own: sorted, a budget cuts the same pairs every run.
  std::sort(m_pairs.begin(), m_pairs.end(), [](const auto& x, const auto& y) {
    return std::make_pair(indexOf(*x.first), indexOf(*x.second)) <
           std::make_pair(indexOf(*y.first), indexOf(*y.second));
  });
  m_microsLeft = m_budget.micros;
  m_nodePairsLeft = m_budget.nodePairs;
  double confidenceSum = 0.0;
  std::uint64_t nodePairsBefore = m_nodePairsLeft;
  double microsBefore = m_microsLeft;
  std::size_t meshLeft = meshPairs;
  for (auto& [a, b] : m_pairs) {
    const MeshData* ma = m_adbQueries ? meshes[indexOf(*a)].get() : nullptr;
    const MeshData* mb = m_adbQueries ? meshes[indexOf(*b)].get() : nullptr;
    PairAnswer answer = ma && mb ? meshPair(*a, *b, *ma, *mb, meshLeft--) : bulletPair(world, *a, *b);
    answer.bodies = {indexOf(*a), indexOf(*b)};
    if (answer.meshMesh) {
      ++record.meshPairs;
      record.cutPairs += answer.cut ? 1 : 0;
      confidenceSum += answer.confidence;
      record.worstConfidence = std::min(record.worstConfidence, answer.confidence);
    }
    m_answers.push_back(answer);
  }
  if (record.meshPairs > 0) record.meanConfidence = confidenceSum / record.meshPairs;
  if (m_budgeted) {
    record.budgetUse = m_budget.kind == BudgetSpec::Kind::Micros
                           ? (m_budget.micros > 0 ? (microsBefore - m_microsLeft) / m_budget.micros : 0.0)
                           : (m_budget.nodePairs > 0
                                  ? static_cast<double>(nodePairsBefore - m_nodePairsLeft) /
                                        static_cast<double>(m_budget.nodePairs)
                                  : 0.0);
  }
}

}  // namespace adb::scene::detail
