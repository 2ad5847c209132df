// Internal: an overlap scene's step. Every broadphase pair gets a yes/no answer: a mesh-mesh
// pair from adb's traversal (stopping at the first hit, or at the quality target) within an
// even share of what is left of the step's budget; any other pair, and every pair under
// GImpact, from Bullet's own pair test. No contact is kept, nothing responds.
#pragma once

#include <btBulletCollisionCommon.h>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/query.h"
#include "adb/scene/scene.h"
#include "adb/scene/scene_world.h"

namespace adb::scene::detail {

using BodyPair = std::pair<std::uint32_t, std::uint32_t>;

struct PairAnswer {
  BodyPair bodies;
  bool overlap = false;
  double confidence = 1.0;
  bool meshMesh = false;  ///< answered by adb's traversal
  bool cut = false;       ///< the budget stopped the traversal before it was sure
};

class OverlapQueries {
 public:
  OverlapQueries(const Scene& scene, Backend backend);

  /// Answers every broadphase pair of `world` (its boxes already updated); `meshes[i]` is
  /// body i's mesh, or nullptr. Fills the record's pairs, confidence and budget use.
  void run(btCollisionWorld& world, const std::vector<std::shared_ptr<const MeshData>>& meshes,
           StepRecord& record);
  const std::vector<PairAnswer>& answers() const { return m_answers; }

 private:
  PairAnswer meshPair(const btCollisionObject& a, const btCollisionObject& b, const MeshData& ma,
                      const MeshData& mb, std::size_t meshPairsLeft);
  static PairAnswer bulletPair(btCollisionWorld& world, btCollisionObject& a, btCollisionObject& b);

  QuerySettings m_settings;
  BudgetSpec m_budget;
  bool m_adbQueries = true;  // false under GImpact: every pair is Bullet's
  bool m_budgeted = false;
  double m_microsLeft = 0.0;
  std::uint64_t m_nodePairsLeft = 0;
  QueryScratch m_scratch;
  std::vector<PairAnswer> m_answers;
  std::vector<std::pair<btCollisionObject*, btCollisionObject*>> m_pairs;  // reused
};

/// The events between two sorted lists of overlapping pairs: `now` minus `before` begin,
/// `before` minus `now` end. `confidence` gives a pair's confidence this step.
template <class Confidence>
void overlapEvents(const std::vector<BodyPair>& before, const std::vector<BodyPair>& now,
                   int step, double time, Confidence confidence,
                   std::vector<OverlapEvent>& out) {
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < now.size()) {
    const bool ended = j == now.size() || (i < before.size() && before[i] < now[j]);
    const bool began = !ended && (i == before.size() || now[j] < before[i]);
    if (ended || began) {
      const BodyPair& p = ended ? before[i] : now[j];
      out.push_back(OverlapEvent{step, time, began, p.first, p.second, confidence(p)});
    }
    if (!began) ++i;
    if (!ended) ++j;
  }
}

}  // namespace adb::scene::detail
